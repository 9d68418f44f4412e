package io.etherware.services.management;

import java.io.IOException;
import java.io.InputStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.security.GeneralSecurityException;
import java.security.KeyStore;
import java.security.KeyStoreException;
import java.security.cert.X509Certificate;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Collections;
import java.util.List;
import java.util.Objects;
import java.util.Set;

/**
 * Configuration of a node's {@link ManagementService}, validated when built. Defaults, in one
 * place:
 * <ul>
 *   <li>{@code allowlist} empty: classes come only from the class path; a jar is refused until
 *       its directory is allowed with {@link Builder#allowDirectory};</li>
 *   <li>{@code trustedSigners} none: a jar is refused until the certificates whose keys sign the
 *       node's plugins are trusted with {@link Builder#trustStore}, {@link Builder#trustedSigners}
 *       or {@link Builder#trustedSigner} (see "Plugins" below);</li>
 *   <li>{@code accessList} empty: every management request that arrived from another node is
 *       refused, and so is every migration into this node (see "Remote management" below);</li>
 *   <li>{@code allowUnauthenticatedLinks} false: a request that arrived over a link that did not
 *       authenticate its peer (plain TCP) is refused, whatever the access list says;</li>
 *   <li>{@code firstMessageWait} 1 s: how long the answer to an upgrade waits for the new logic's
 *       first message, to report the swap gap; after that it is answered with {@code gapNs = -1};</li>
 *   <li>{@code migrationStepTimeout} 2 s: how long the source of a migration waits for each answer
 *       of the target (prepare, install, hand-over); a step without an answer fails the migration
 *       and the component resumes at the source. Also how long a target waits, after the source of
 *       a component installed there left without a goodbye, before it takes the component over;</li>
 *   <li>{@code handoverWait} 5 s: how long a target keeps a migrated component held, waiting for the
 *       source's hand-over, before it gives the migration up and removes the component (the source
 *       has then resumed it after its own step timeout; one that left without a goodbye has had the
 *       component taken over before); an instance prepared for a
 *       migration whose state never came is discarded after {@code settleWait + 2 ×
 *       migrationStepTimeout + handoverWait} (9.1 s by default);</li>
 *   <li>{@code maxQueuedOperations} 8: how many upgrades and migrations away from this node may
 *       wait behind the one in progress (they run one at a time, in arrival order), and how many
 *       migration PREPARE steps into it may wait behind the one being loaded; a request beyond
 *       that is refused at once with {@link ManagementFailure.Reason#BUSY};</li>
 *   <li>{@code classLoader} the system class loader: where class-path implementations come from,
 *       and the parent of the jars' class loaders.</li>
 * </ul>
 *
 * <h2>Remote management</h2>
 * Who asks is decided from the connection, never from the message (DESIGN decision 11): a request
 * is local when it was made on this node ({@link io.etherware.core.message.Message#origin()} is
 * null) and is then served. A request that arrived from another node is served only when
 * <ol>
 *   <li>it came straight from the node that made it ({@code origin.hops() == 0}): a relay must not
 *       lend its rights, so a relayed request is refused even if its maker is allowed;</li>
 *   <li>its link authenticated that node (TLS), unless {@link Builder#allowUnauthenticatedLinks}
 *       was chosen for a loopback development setup;</li>
 *   <li>an {@link AccessRule} of the access list permits that node the operation on that component
 *       ({@link Builder#allowRemote}; the matching rule is on {@link AccessRule}).</li>
 * </ol>
 * The same rule guards a migration into this node: each step (prepare, install, hand-over) must come
 * from a node the list allows to {@link AccessRule.Operation#MIGRATE MIGRATE} that profile, and
 * install and hand-over from the node that prepared it; and the source of a migration takes the
 * target's answers only if they came straight from the target. A refusal is counted
 * ({@link ManagementService#refusedCount()}), logged at WARN with the node, the operation and the
 * profile, and answered with a {@link ManagementFailure} of reason
 * {@link ManagementFailure.Reason#REMOTE_REFUSED} that says what to configure.
 *
 * <h2>Plugins</h2>
 * A jar is loaded only if its canonical path lies in an allowlisted directory and every class and
 * resource in it (all entries but the manifest and the signature files in {@code META-INF/}) is
 * signed, with {@code jarsigner}, by a key whose certificate the node trusts: the signer's
 * certificate is a trusted one, or its certificate chain validates (PKIX, no revocation check)
 * up to a trusted certificate. The certificates of the chain must be valid now; a signature
 * time stamp is not taken into account, so re-sign plugins before their certificate expires. The
 * node verifies a private copy of the jar and loads from that copy, so the file cannot change
 * between the check and the loading. Classes from the class path need no signature.
 *
 * <p>Immutable; safe to share between threads.
 *
 * @param allowlist            the directories jars may be loaded from, canonical (symbolic links
 *                             resolved)
 * @param trustedSigners       the certificates whose keys (or whose CAs' keys) plugins must be
 *                             signed with
 * @param accessList           what other nodes may ask for
 * @param allowUnauthenticatedLinks whether the access list also applies to requests that arrived
 *                             over links that did not authenticate their peer
 * @param firstMessageWaitNs   how long an upgrade's answer waits for the new logic's first message
 *                             (also a migration's hand-over answer, for the gap)
 * @param migrationStepTimeoutNs how long a migration's source waits for each answer of the target
 * @param handoverWaitNs       how long a migration's target waits for the hand-over
 * @param settleWaitNs         how long a migration's source waits, before it holds the component,
 *                             and an upgrade before it swaps the logic, for the outcomes of the
 *                             component's own requests in flight (a migration: and for the
 *                             messages of other components already queued for it)
 * @param maxQueuedOperations  how many operations may wait behind the one in progress (each of
 *                             the two queues: operations of this node, PREPARE steps into it)
 * @param classLoader          the node's class loader for implementations
 */
public record ManagementConfig(List<Path> allowlist, List<X509Certificate> trustedSigners, List<AccessRule> accessList,
                               boolean allowUnauthenticatedLinks, long firstMessageWaitNs, long migrationStepTimeoutNs,
                               long handoverWaitNs, long settleWaitNs, int maxQueuedOperations,
                               ClassLoader classLoader) {

    /**
     * Copies the lists and checks the fields.
     *
     * @throws NullPointerException     if a list, an element or {@code classLoader} is null
     * @throws IllegalArgumentException if an allowlist entry is not absolute and normalized,
     *                                  {@code firstMessageWaitNs} &lt; 0,
     *                                  {@code migrationStepTimeoutNs} &lt;= 0, or
     *                                  {@code handoverWaitNs} &lt;= {@code migrationStepTimeoutNs},
     *                                  or {@code settleWaitNs} is negative or not below
     *                                  {@code migrationStepTimeoutNs}, or
     *                                  {@code maxQueuedOperations} &lt; 0
     */
    public ManagementConfig {
        allowlist = List.copyOf(allowlist);
        trustedSigners = List.copyOf(trustedSigners);
        accessList = List.copyOf(accessList);
        for (Path directory : allowlist) {
            if (!directory.isAbsolute() || !directory.equals(directory.normalize())) {
                throw new IllegalArgumentException("allowlist entry '" + directory
                        + "' must be canonical; use ManagementConfig.builder().allowDirectory(path)");
            }
        }
        if (firstMessageWaitNs < 0) {
            throw new IllegalArgumentException("firstMessageWaitNs=" + firstMessageWaitNs
                    + " must be >= 0 (0 answers at once, without the gap)");
        }
        if (migrationStepTimeoutNs <= 0) {
            throw new IllegalArgumentException("migrationStepTimeoutNs=" + migrationStepTimeoutNs + " must be > 0");
        }
        if (settleWaitNs < 0 || settleWaitNs >= migrationStepTimeoutNs) {
            throw new IllegalArgumentException("settleWaitNs=" + settleWaitNs + " must be >= 0 and below"
                    + " migrationStepTimeoutNs=" + migrationStepTimeoutNs);
        }
        if (handoverWaitNs <= migrationStepTimeoutNs) {
            throw new IllegalArgumentException("handoverWaitNs=" + handoverWaitNs + " must be > migrationStepTimeoutNs="
                    + migrationStepTimeoutNs + ": a target must not give up a migration its source still waits for");
        }
        if (maxQueuedOperations < 0) {
            throw new IllegalArgumentException("maxQueuedOperations=" + maxQueuedOperations
                    + " must be >= 0 (0 refuses any operation while one is in progress)");
        }
        Objects.requireNonNull(classLoader, "classLoader=null: leave the default (the system class loader)");
    }

    /**
     * How long after a migration's INSTALL its source may still look for the target's process
     * having left without a goodbye, to resume the component itself (see the package
     * documentation, "When a node dies during a migration"): the INSTALL's answer, the
     * HANDOVER's with the target's first-message wait, and the step the target must stay away,
     * that is
     * {@code 2 × migrationStepTimeoutNs + firstMessageWaitNs} (5 s by default), plus the time the
     * relocation itself takes. The source's messenger forgets a peer after its
     * {@link io.etherware.services.network.NetworkConfig#peerDownGraceNs()} (10 s by default),
     * which must exceed this for the resume to see the target gone;
     * {@link ManagementService#install(io.etherware.core.kernel.EtherwareNode, ManagementConfig,
     * io.etherware.services.network.NetworkMessenger)} warns if it does not.
     *
     * @return the time in ns, {@link Long#MAX_VALUE} if it overflows
     */
    public long targetWatchNs() {
        try {
            return Math.addExact(Math.multiplyExact(2, migrationStepTimeoutNs), firstMessageWaitNs);
        } catch (ArithmeticException e) {
            return Long.MAX_VALUE;
        }
    }

    /**
     * The defaults listed above: local management only, no plugins.
     *
     * @return a configuration with every default
     */
    public static ManagementConfig defaults() {
        return builder().build();
    }

    /**
     * A builder holding the defaults listed above.
     *
     * @return a new builder
     */
    public static Builder builder() {
        return new Builder();
    }

    /** Builds a {@link ManagementConfig}; not thread-safe. */
    public static final class Builder {
        private final List<Path> allowlist = new ArrayList<>();
        private final List<X509Certificate> trustedSigners = new ArrayList<>();
        private final List<AccessRule> accessList = new ArrayList<>();
        private boolean allowUnauthenticatedLinks;
        private long firstMessageWaitNs = Duration.ofSeconds(1).toNanos();
        private long migrationStepTimeoutNs = Duration.ofSeconds(2).toNanos();
        private long handoverWaitNs = Duration.ofSeconds(5).toNanos();
        private long settleWaitNs = Duration.ofMillis(100).toNanos();
        private int maxQueuedOperations = 8;
        private ClassLoader classLoader = ClassLoader.getSystemClassLoader();

        Builder() {
        }

        /**
         * Allows jars in {@code directory} and its subdirectories. The directory is resolved to
         * its canonical path now (symbolic links followed), so it must exist. Default: no
         * directory, so no jar is loaded.
         *
         * @param directory a directory on this node
         * @return this builder
         * @throws IllegalArgumentException if it does not exist or is not a directory
         */
        public Builder allowDirectory(Path directory) {
            Objects.requireNonNull(directory, "directory");
            Path canonical;
            try {
                canonical = directory.toRealPath();
            } catch (IOException e) {
                throw new IllegalArgumentException("allowDirectory='" + directory + "' cannot be resolved (" + e
                        + "); create the directory first", e);
            }
            if (!Files.isDirectory(canonical)) {
                throw new IllegalArgumentException("allowDirectory='" + directory + "' is not a directory");
            }
            allowlist.add(canonical);
            return this;
        }

        /**
         * Lets node {@code node} ({@code "*"}: any node) ask this node for {@code operations} on
         * the components {@code profilePattern} matches; see {@link AccessRule} for the matching.
         * Each call adds a rule; a request is served if any rule permits it. Default: no rule, so
         * every request and migration step from another node is refused.
         *
         * @param node           a node id, or {@code "*"} for every node
         * @param operations     what that node may ask for; not empty
         * @param profilePattern which components: a profile query whose role may contain
         *                       {@code *}, or {@code "*"} for every component
         * @return this builder
         * @throws IllegalArgumentException if the node id, the operations or the pattern is not
         *                                  valid (see {@link AccessRule})
         */
        public Builder allowRemote(String node, Set<AccessRule.Operation> operations, String profilePattern) {
            return allowRemote(new AccessRule(node, operations, profilePattern));
        }

        /**
         * Adds {@code rule} to the access list.
         *
         * @param rule the rule
         * @return this builder
         * @throws NullPointerException if {@code rule} is null
         */
        public Builder allowRemote(AccessRule rule) {
            accessList.add(Objects.requireNonNull(rule, "rule"));
            return this;
        }

        /**
         * Also applies the access list to requests that arrived over links that did not
         * authenticate their peer (plain TCP), whose node id is only the peer's word. For a
         * loopback development setup; between machines, connect the nodes with TLS instead.
         * Default false: such requests are refused.
         *
         * @param value true to let the access list decide for unauthenticated links too
         * @return this builder
         */
        public Builder allowUnauthenticatedLinks(boolean value) {
            allowUnauthenticatedLinks = value;
            return this;
        }

        /**
         * Trusts plugins signed with the key of {@code certificate}, or of a certificate it issued.
         * Default: no trusted signer, so no jar is loaded.
         *
         * @param certificate the signer's or its CA's certificate
         * @return this builder
         * @throws NullPointerException if {@code certificate} is null
         */
        public Builder trustedSigner(X509Certificate certificate) {
            trustedSigners.add(Objects.requireNonNull(certificate, "certificate"));
            return this;
        }

        /**
         * Trusts the certificates of {@code store}'s trusted-certificate entries (those that
         * {@code keytool -importcert} makes) as plugin signers.
         *
         * @param store a loaded key store
         * @return this builder
         * @throws IllegalArgumentException if it holds none, or cannot be read
         */
        public Builder trustedSigners(KeyStore store) {
            Objects.requireNonNull(store, "store");
            List<X509Certificate> found = new ArrayList<>();
            List<String> aliases;
            try {
                aliases = Collections.list(store.aliases());
                for (String alias : aliases) {
                    if (store.isCertificateEntry(alias) && store.getCertificate(alias) instanceof X509Certificate x509) {
                        found.add(x509);
                    }
                }
            } catch (KeyStoreException e) {
                throw new IllegalArgumentException("trustedSigners: the key store cannot be read (" + e
                        + "); load it before passing it", e);
            }
            if (found.isEmpty()) {
                throw new IllegalArgumentException("trustedSigners: the key store holds no trusted certificate entry"
                        + " (aliases " + aliases + "); import the plugin signer's certificate with keytool -importcert");
            }
            trustedSigners.addAll(found);
            return this;
        }

        /**
         * Trusts the certificates of the PKCS12 trust store {@code file} (see
         * {@link #trustedSigners(KeyStore)}), opened with {@code password}. Reads the file now.
         *
         * @param file     the PKCS12 trust store
         * @param password its password
         * @return this builder
         * @throws IllegalArgumentException if it cannot be read or holds no certificate
         */
        public Builder trustStore(Path file, char[] password) {
            Objects.requireNonNull(file, "file");
            KeyStore store;
            try (InputStream in = Files.newInputStream(file)) {
                store = KeyStore.getInstance("PKCS12");
                store.load(in, password);
            } catch (IOException | GeneralSecurityException e) {
                throw new IllegalArgumentException("trustStore='" + file + "' cannot be read as PKCS12 (" + e
                        + "); make it with keytool -importcert -storetype PKCS12 and check the password", e);
            }
            try {
                return trustedSigners(store);
            } catch (IllegalArgumentException e) {
                throw new IllegalArgumentException("trustStore='" + file + "': " + e.getMessage(), e);
            }
        }

        /**
         * How long an upgrade's answer waits for the new logic's first message, to report the
         * swap gap; after it, the answer goes out with {@code gapNs = -1}. Also bounds a
         * migration's hand-over answer at a target. Default 1 s.
         *
         * @param value &gt;= 0 (0: answer at once, without the gap)
         * @return this builder
         * @throws IllegalArgumentException if {@code value} is negative
         */
        public Builder firstMessageWait(Duration value) {
            Objects.requireNonNull(value, "firstMessageWait");
            if (value.isNegative()) {
                throw new IllegalArgumentException("firstMessageWait=" + value + " must be >= 0");
            }
            firstMessageWaitNs = value.toNanos();
            return this;
        }

        /**
         * How long a migration's source waits for each answer of the target (prepare, install,
         * hand-over); a step without an answer fails the migration and the component resumes at
         * the source. Default 2 s.
         *
         * @param value &gt; 0, and shorter than the {@link #handoverWait} (checked by
         *              {@link #build()})
         * @return this builder
         */
        public Builder migrationStepTimeout(Duration value) {
            Objects.requireNonNull(value, "migrationStepTimeout");
            migrationStepTimeoutNs = value.toNanos();
            return this;
        }

        /**
         * How long a migration's target keeps the arrived component held for the hand-over before
         * it gives the migration up and removes the component. Default 5 s.
         *
         * @param value longer than the {@link #migrationStepTimeout}, so a target never gives up a
         *              migration its source still waits for (checked by {@link #build()})
         * @return this builder
         */
        public Builder handoverWait(Duration value) {
            Objects.requireNonNull(value, "handoverWait");
            handoverWaitNs = value.toNanos();
            return this;
        }

        /**
         * How long a migration's source lets the component run on, before it holds it, for the
         * outcomes of the component's own requests in flight (replies, failures, timeouts) to
         * reach it at the source, where their callbacks live: the component is held at its first
         * message boundary without a request in flight (see
         * {@link io.etherware.core.kernel.ComponentHost#holdAsync(io.etherware.core.message.Profile, Duration)}).
         * A component still waiting after this long is held anyway, and the outcomes that come
         * later are handed to the stopped instance at the source, not to the moved one. An
         * upgrade waits the same way before it swaps the logic, so that an outcome reaches the
         * old logic's callback, not a replaced one. Default 100 ms: a few round trips of a
         * control loop. Zero holds (or swaps) at the next boundary.
         *
         * @param value &gt;= 0, and shorter than the {@link #migrationStepTimeout} (checked by
         *              {@link #build()})
         * @return this builder
         */
        public Builder settleWait(Duration value) {
            Objects.requireNonNull(value, "settleWait");
            settleWaitNs = value.toNanos();
            return this;
        }

        /**
         * How many management operations may wait while one is in progress. A node runs its
         * upgrades and its migrations away one at a time, in the order they arrived (a migration
         * blocks for its target's answers), and loads the classes of migrations into it one at a
         * time on a thread of their own (so two nodes migrating to each other do not wait for each
         * other). Beyond this many waiting in either queue, a request is answered at once with
         * {@link ManagementFailure.Reason#BUSY}, naming the node and the bound: ask again later.
         * Default 8.
         *
         * @param value &gt;= 0; 0 refuses any request while one is in progress
         * @return this builder
         * @throws IllegalArgumentException if {@code value} is negative
         */
        public Builder maxQueuedOperations(int value) {
            if (value < 0) {
                throw new IllegalArgumentException("maxQueuedOperations=" + value + " must be >= 0");
            }
            maxQueuedOperations = value;
            return this;
        }

        /**
         * Where class-path implementations come from, and the parent of jar class loaders.
         * Default: the system class loader.
         *
         * @param value the class loader
         * @return this builder
         * @throws NullPointerException if {@code value} is null
         */
        public Builder classLoader(ClassLoader value) {
            classLoader = Objects.requireNonNull(value, "classLoader");
            return this;
        }

        /**
         * The validated configuration. The builder may be used again afterwards.
         *
         * @return the configuration
         * @throws IllegalArgumentException if the handover wait is not longer than the migration
         *                                  step timeout, or the step timeout is not positive
         */
        public ManagementConfig build() {
            return new ManagementConfig(allowlist, trustedSigners, accessList, allowUnauthenticatedLinks,
                    firstMessageWaitNs, migrationStepTimeoutNs, handoverWaitNs, settleWaitNs, maxQueuedOperations,
                    classLoader);
        }
    }
}
