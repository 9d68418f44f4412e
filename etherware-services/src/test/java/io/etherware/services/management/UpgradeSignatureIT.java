package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import example.counter.Journal;
import example.counter.SequenceCounter;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.scheduler.FifoScheduler;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Arrays;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import java.util.function.UnaryOperator;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * Upgrades from jars need a signature by a trusted key: the keys are made here by keytool and the
 * jars signed by jarsigner. Every refused jar carries a static initializer that records that it
 * ran, so each refusal also shows that none of the jar's code ran.
 */
class UpgradeSignatureIT {

    private static final String CLASS = "signed.CounterV2";
    private static final String CLASS_FILE = "signed/CounterV2.class";

    @TempDir
    static Path keys;
    private static JarBuilder.SigningKey trusted;
    private static JarBuilder.SigningKey other;

    @TempDir
    Path allowed;

    @BeforeAll
    static void makeKeys() throws Exception {
        trusted = JarBuilder.newKey(keys, "plugin-signer", 0, 30);
        other = JarBuilder.newKey(keys, "someone-else", 0, 30);
    }

    /** A jar with {@link #CLASS}, whose static initializer sets system property {@code marker}. */
    private Path jar(String name, String version, String marker) throws Exception {
        return JarBuilder.build(allowed.resolve(name), Map.of(CLASS, """
                package signed;
                public class CounterV2 extends example.counter.SequenceCounter {
                    static { System.setProperty("%s", "ran"); }
                    public CounterV2(String journalName) { super(journalName); }
                    @Override protected String version() { return "%s"; }
                }
                """.formatted(marker, version)));
    }

    private EtherwareNode node(String nodeId, String journal, UnaryOperator<ManagementConfig.Builder> trust) {
        var node = EtherwareNode.builder().nodeId(nodeId).scheduler(FifoScheduler::new).build();
        ManagementService.install(node, trust.apply(ManagementConfig.builder().allowDirectory(allowed)).build());
        node.add(UpgradeIT.COUNTER, () -> new SequenceCounter(journal));
        return node.start();
    }

    private EtherwareNode trustingNode(String nodeId, String journal) {
        return node(nodeId, journal, config -> config.trustedSigner(trusted.certificate()));
    }

    /** Asks for the upgrade, expects UNTRUSTED_CODE, and checks that V1 serves on and no jar code ran. */
    private static ManagementFailure assertRefused(EtherwareNode node, Journal journal, Path jar, String marker)
            throws Exception {
        var failure = assertInstanceOf(ManagementException.class, UpgradeIT.assertFailed(Management.upgrade(node,
                node.nodeId(), UpgradeIT.COUNTER, Implementation.fromJar(jar, CLASS).withConfiguration(marker))))
                .failure();
        assertEquals(ManagementFailure.Reason.UNTRUSTED_CODE, failure.reason(), failure.error());
        assertTrue(failure.error().contains(jar.toRealPath().toString()), "names the jar: " + failure.error());
        assertNull(System.getProperty(marker), "no code of the refused jar ran");
        assertEquals(SequenceCounter.class, node.shell(UpgradeIT.COUNTER).logicType(), "V1 serves on");
        UpgradeIT.sendAndAwait(node, journal, 0, 1);
        return failure;
    }

    @Test
    void shouldUpgradeFromAJarSignedByAKeyOfTheTrustStoreMadeWithKeytool() throws Exception {
        Path jar = JarBuilder.sign(jar("good.jar", "v2-signed", "signature.good"), trusted);
        Path trustStore = JarBuilder.trustStore(keys.resolve("plugin-trust.p12"), trusted);
        Journal journal = Journal.create("signature-good");
        try (var node = node("signed-good", "signature-good", config -> config.trustStore(trustStore,
                JarBuilder.PASSWORD.toCharArray()))) {
            UpgradeIT.sendAndAwait(node, journal, 0, 2);
            UpgradeResult result = Management.upgrade(node, node.nodeId(), UpgradeIT.COUNTER,
                    Implementation.fromJar(jar, CLASS).withConfiguration("signature-good")).get(30, TimeUnit.SECONDS);
            UpgradeIT.sendAndAwait(node, journal, 2, 4);

            assertEquals(CLASS, result.newImplementation());
            assertEquals(jar.toRealPath().toString(), result.source());
            assertEquals(List.of("v1", "v1", "v2-signed", "v2-signed"),
                    journal.entries().stream().map(Journal.Entry::version).toList());
            Class<?> running = node.shell(UpgradeIT.COUNTER).logicType();
            assertEquals(CLASS, running.getName());
            var signers = running.getProtectionDomain().getCodeSource().getCodeSigners();
            assertNotNull(signers, "the class was defined from the signed jar");
            assertEquals(trusted.certificate(), signers[0].getSignerCertPath().getCertificates().getFirst());
        }
    }

    @Test
    void shouldUpgradeFromAJarSignedByAKeyWhoseCertificateATrustedCertificateIssued() throws Exception {
        JarBuilder.SigningKey team = JarBuilder.newKeyIssuedBy(keys, "team-signer", trusted);
        Path jar = JarBuilder.sign(jar("issued.jar", "v2-issued", "signature.issued"), team);
        Journal journal = Journal.create("signature-issued");
        try (var node = trustingNode("signed-issued", "signature-issued")) {
            UpgradeResult result = Management.upgrade(node, node.nodeId(), UpgradeIT.COUNTER,
                    Implementation.fromJar(jar, CLASS).withConfiguration("signature-issued")).get(30, TimeUnit.SECONDS);
            assertEquals(CLASS, result.newImplementation());
            UpgradeIT.sendAndAwait(node, journal, 0, 1);
            assertEquals("v2-issued", journal.entries().getFirst().version());
        }
    }

    @Test
    void shouldRefuseAnUnsignedJar() throws Exception {
        Path jar = jar("unsigned.jar", "v2", "signature.unsigned");
        Journal journal = Journal.create("signature-unsigned");
        try (var node = trustingNode("signed-unsigned", "signature-unsigned")) {
            var failure = assertRefused(node, journal, jar, "signature.unsigned");
            assertTrue(failure.error().contains("is not signed"), failure.error());
        }
    }

    @Test
    void shouldRefuseAJarSignedByAKeyTheNodeDoesNotTrust() throws Exception {
        Path jar = JarBuilder.sign(jar("other.jar", "v2", "signature.other"), other);
        Journal journal = Journal.create("signature-other");
        try (var node = trustingNode("signed-other", "signature-other")) {
            var failure = assertRefused(node, journal, jar, "signature.other");
            assertTrue(failure.error().contains("is not signed by a key this node trusts"), failure.error());
            assertTrue(failure.error().contains("CN=someone-else"), failure.error());
        }
    }

    @Test
    void shouldRefuseAJarWhoseClassWasReplacedAfterSigning() throws Exception {
        Path jar = JarBuilder.sign(jar("tampered.jar", "v2", "signature.tampered"), trusted);
        // The attacker's class: compiled the same way, different code, put in place of the signed one.
        byte[] evil = JarBuilder.entry(jar("evil-build.jar", "evil", "signature.tampered"), CLASS_FILE);
        assertFalse(Arrays.equals(evil, JarBuilder.entry(jar, CLASS_FILE)), "another class than the signed one");
        JarBuilder.replaceEntry(jar, CLASS_FILE, evil);
        Journal journal = Journal.create("signature-tampered");
        try (var node = trustingNode("signed-tampered", "signature-tampered")) {
            var failure = assertRefused(node, journal, jar, "signature.tampered");
            assertTrue(failure.error().contains("fails signature verification"), failure.error());
        }
    }

    @Test
    void shouldRefuseAJarWithAnEntryAddedAfterSigning() throws Exception {
        Path jar = JarBuilder.sign(jar("partly.jar", "v2", "signature.partly"), trusted);
        JarBuilder.replaceEntry(jar, "signed/config.properties", "gain=100".getBytes());
        Journal journal = Journal.create("signature-partly");
        try (var node = trustingNode("signed-partly", "signature-partly")) {
            var failure = assertRefused(node, journal, jar, "signature.partly");
            assertTrue(failure.error().contains("only partly signed: no signature on entry 'signed/config.properties'"),
                    failure.error());
        }
    }

    @Test
    void shouldRefuseAJarSignedWithAnExpiredCertificate() throws Exception {
        JarBuilder.SigningKey expired = JarBuilder.newKey(keys, "expired-signer", -10, 5);
        Path jar = JarBuilder.sign(jar("expired.jar", "v2", "signature.expired"), expired);
        Journal journal = Journal.create("signature-expired");
        try (var node = node("signed-expired", "signature-expired",
                config -> config.trustedSigner(expired.certificate()))) {
            var failure = assertRefused(node, journal, jar, "signature.expired");
            assertTrue(failure.error().contains("not valid now"), failure.error());
        }
    }

    @Test
    void shouldRefuseEveryJarAndSayHowToTrustASignerWhenTheNodeTrustsNone() throws Exception {
        Path jar = JarBuilder.sign(jar("no-trust.jar", "v2", "signature.none"), trusted);
        Journal journal = Journal.create("signature-none");
        try (var node = node("signed-none", "signature-none", config -> config)) {
            var failure = assertRefused(node, journal, jar, "signature.none");
            assertTrue(failure.error().contains("trusts no plugin signer"), failure.error());
            assertTrue(failure.error().contains("ManagementConfig.builder().trustStore("), failure.error());
        }
    }

    @Test
    void shouldRefuseATrustStoreWithoutCertificatesOrWithTheWrongPassword() throws Exception {
        var noCertificate = assertThrows(IllegalArgumentException.class,
                () -> ManagementConfig.builder().trustStore(trusted.keyStore(), JarBuilder.PASSWORD.toCharArray()));
        assertTrue(noCertificate.getMessage().contains("no trusted certificate entry"), noCertificate.getMessage());
        Path store = JarBuilder.trustStore(keys.resolve("password-trust.p12"), other);
        var wrongPassword = assertThrows(IllegalArgumentException.class,
                () -> ManagementConfig.builder().trustStore(store, "wrong".toCharArray()));
        assertTrue(wrongPassword.getMessage().contains("trustStore='" + store + "'"), wrongPassword.getMessage());
        assertTrue(Files.isRegularFile(store));
    }
}
