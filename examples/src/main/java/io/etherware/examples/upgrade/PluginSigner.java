package io.etherware.examples.upgrade;

import java.io.IOException;
import java.io.InputStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.security.GeneralSecurityException;
import java.security.KeyStore;
import java.security.MessageDigest;
import java.security.SecureRandom;
import java.security.cert.X509Certificate;
import java.util.HexFormat;
import java.util.List;
import java.util.concurrent.TimeUnit;

/**
 * Signs the upgrade scenario's plugin jar for one run, because a node loads plugin code only when
 * a key it trusts signed it: makes a throw-away key with the JDK's {@code keytool} into the run's
 * output directory, signs a copy of the jar there with {@code jarsigner}, and hands back the copy
 * and the certificate the node is then told to trust. A deployment signs its plugins once with its
 * own key instead (see the README, "Signed plugins").
 *
 * <p>Not thread-safe: one thread runs it, before the scenario starts.
 */
final class PluginSigner {

    private static final String ALIAS = "etherware-demo-plugins";
    private static final long TOOL_TIMEOUT_S = 120;

    /**
     * A signed copy of the plugin jar.
     *
     * @param jar         the signed copy, alone in its directory (the node allowlists that one)
     * @param keyStore    where the run's key is (its password was random and is forgotten)
     * @param certificate the key's certificate, which the node trusts
     */
    record Signed(Path jar, Path keyStore, X509Certificate certificate) {

        /** The line the scenario prints about it. */
        String line() {
            return "plugin: signed " + jar + " with a key made for this run (" + keyStore + "); the node trusts only"
                    + " its certificate, " + certificate.getSubjectX500Principal().getName() + ", SHA-256 "
                    + fingerprint(certificate);
        }
    }

    private PluginSigner() {
    }

    /**
     * Signs a copy of {@code jar} into {@code out/plugin/}, with a new key in
     * {@code out/plugin-signing/}.
     *
     * @throws IOException if the files cannot be written or keytool or jarsigner fail (they need
     *                     a JDK, not a bare runtime)
     */
    static Signed signForThisRun(Path jar, Path out) throws IOException {
        Path keys = Files.createDirectories(out.resolve("plugin-signing"));
        Path keyStore = keys.resolve("plugin-signer.p12");
        Files.deleteIfExists(keyStore);
        Path plugins = Files.createDirectories(out.resolve("plugin"));
        Path signed = plugins.resolve(jar.getFileName());
        Files.copy(jar, signed, StandardCopyOption.REPLACE_EXISTING);
        byte[] secret = new byte[16];
        new SecureRandom().nextBytes(secret);
        String password = HexFormat.of().formatHex(secret);
        run(List.of(tool("keytool"), "-genkeypair", "-keyalg", "EC", "-groupname", "secp256r1", "-alias", ALIAS,
                "-dname", "CN=etherware-demo plugin signer (one run)", "-validity", "2", "-keystore",
                keyStore.toString(), "-storetype", "PKCS12", "-storepass", password, "-keypass", password));
        run(List.of(tool("jarsigner"), "-keystore", keyStore.toString(), "-storepass", password, "-keypass", password,
                signed.toString(), ALIAS));
        try (InputStream in = Files.newInputStream(keyStore)) {
            KeyStore store = KeyStore.getInstance("PKCS12");
            store.load(in, password.toCharArray());
            return new Signed(signed, keyStore, (X509Certificate) store.getCertificate(ALIAS));
        } catch (GeneralSecurityException e) {
            throw new IOException("the key store " + keyStore + " that keytool made cannot be read: " + e, e);
        }
    }

    private static String tool(String name) throws IOException {
        Path tool = Path.of(System.getProperty("java.home"), "bin", name);
        if (!Files.isExecutable(tool)) {
            throw new IOException(tool + " is missing: run the scenario on a JDK (it signs the plugin with keytool and"
                    + " jarsigner)");
        }
        return tool.toString();
    }

    private static void run(List<String> command) throws IOException {
        Process process = new ProcessBuilder(command).redirectErrorStream(true).start();
        process.getOutputStream().close();
        String output = new String(process.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        try {
            if (!process.waitFor(TOOL_TIMEOUT_S, TimeUnit.SECONDS)) {
                process.destroyForcibly();
                throw new IOException(command.getFirst() + " did not finish within " + TOOL_TIMEOUT_S + " s");
            }
        } catch (InterruptedException e) {
            process.destroyForcibly();
            Thread.currentThread().interrupt();
            throw new IOException("interrupted while running " + command.getFirst(), e);
        }
        if (process.exitValue() != 0) {
            throw new IOException(command.getFirst() + " failed (exit " + process.exitValue() + "): " + output.strip());
        }
    }

    private static String fingerprint(X509Certificate certificate) {
        try {
            byte[] digest = MessageDigest.getInstance("SHA-256").digest(certificate.getEncoded());
            return HexFormat.ofDelimiter(":").withUpperCase().formatHex(digest);
        } catch (GeneralSecurityException e) {
            return "unavailable (" + e + ")";
        }
    }
}
