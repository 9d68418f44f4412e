package io.etherware.services.management;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;

/**
 * Configuration of a node's {@link ManagementService}, validated when built. Defaults, in one
 * place:
 * <ul>
 *   <li>{@code allowlist} empty: classes come only from the class path; a jar is refused until
 *       its directory is allowed with {@link Builder#allowDirectory};</li>
 *   <li>{@code acceptRemoteRequests} false: requests made on another node are refused (there is no
 *       authentication of links yet, so a peer could otherwise run code here);</li>
 *   <li>{@code firstMessageWait} 1 s: how long the answer to an upgrade waits for the new logic's
 *       first message, to report the swap gap; after that it is answered with {@code gapNs = -1};</li>
 *   <li>{@code migrationStepTimeout} 2 s: how long the source of a migration waits for each answer
 *       of the target (prepare, install, hand-over); a step without an answer fails the migration
 *       and the component resumes at the source;</li>
 *   <li>{@code handoverWait} 5 s: how long a target keeps a migrated component held, waiting for the
 *       source's hand-over, before it gives the migration up and removes the component (the source
 *       has then resumed it after its own step timeout);</li>
 *   <li>{@code classLoader} the system class loader: where class-path implementations come from,
 *       and the parent of the jars' class loaders.</li>
 * </ul>
 *
 * <p>Immutable; safe to share between threads.
 *
 * @param allowlist            the directories jars may be loaded from, canonical (symbolic links
 *                             resolved)
 * @param acceptRemoteRequests whether requests made on another node are served
 * @param firstMessageWaitNs   how long an upgrade's answer waits for the new logic's first message
 *                             (also a migration's hand-over answer, for the gap)
 * @param migrationStepTimeoutNs how long a migration's source waits for each answer of the target
 * @param handoverWaitNs       how long a migration's target waits for the hand-over
 * @param classLoader          the node's class loader for implementations
 */
public record ManagementConfig(List<Path> allowlist, boolean acceptRemoteRequests, long firstMessageWaitNs,
                               long migrationStepTimeoutNs, long handoverWaitNs, ClassLoader classLoader) {

    public ManagementConfig {
        allowlist = List.copyOf(allowlist);
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
        if (handoverWaitNs <= migrationStepTimeoutNs) {
            throw new IllegalArgumentException("handoverWaitNs=" + handoverWaitNs + " must be > migrationStepTimeoutNs="
                    + migrationStepTimeoutNs + ": a target must not give up a migration its source still waits for");
        }
        Objects.requireNonNull(classLoader, "classLoader=null: leave the default (the system class loader)");
    }

    /** The defaults listed above. */
    public static ManagementConfig defaults() {
        return builder().build();
    }

    public static Builder builder() {
        return new Builder();
    }

    /** Builds a {@link ManagementConfig}; not thread-safe. */
    public static final class Builder {
        private final List<Path> allowlist = new ArrayList<>();
        private boolean acceptRemoteRequests;
        private long firstMessageWaitNs = Duration.ofSeconds(1).toNanos();
        private long migrationStepTimeoutNs = Duration.ofSeconds(2).toNanos();
        private long handoverWaitNs = Duration.ofSeconds(5).toNanos();
        private ClassLoader classLoader = ClassLoader.getSystemClassLoader();

        Builder() {
        }

        /**
         * Allows jars in {@code directory} and its subdirectories. The directory is resolved to
         * its canonical path now (symbolic links followed), so it must exist.
         *
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

        /** Serve management requests made on other nodes (default false). */
        public Builder acceptRemoteRequests(boolean value) {
            acceptRemoteRequests = value;
            return this;
        }

        /** How long an upgrade's answer waits for the new logic's first message (default 1 s). */
        public Builder firstMessageWait(Duration value) {
            Objects.requireNonNull(value, "firstMessageWait");
            if (value.isNegative()) {
                throw new IllegalArgumentException("firstMessageWait=" + value + " must be >= 0");
            }
            firstMessageWaitNs = value.toNanos();
            return this;
        }

        /** How long a migration's source waits for each answer of the target (default 2 s). */
        public Builder migrationStepTimeout(Duration value) {
            Objects.requireNonNull(value, "migrationStepTimeout");
            migrationStepTimeoutNs = value.toNanos();
            return this;
        }

        /** How long a migration's target keeps the arrived component held for the hand-over (default 5 s). */
        public Builder handoverWait(Duration value) {
            Objects.requireNonNull(value, "handoverWait");
            handoverWaitNs = value.toNanos();
            return this;
        }

        /** Where class-path implementations come from, and the parent of jar class loaders. */
        public Builder classLoader(ClassLoader value) {
            classLoader = Objects.requireNonNull(value, "classLoader");
            return this;
        }

        /** The validated configuration. */
        public ManagementConfig build() {
            return new ManagementConfig(allowlist, acceptRemoteRequests, firstMessageWaitNs, migrationStepTimeoutNs,
                    handoverWaitNs, classLoader);
        }
    }
}
