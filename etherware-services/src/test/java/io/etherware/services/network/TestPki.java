package io.etherware.services.network;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.TimeUnit;

/**
 * A deployment's certificates, made at test time with the JDK's {@code keytool} exactly as the
 * README tells an operator to (no private key is ever in git): a CA, and per node a PKCS#12 key
 * store whose certificate, signed by the CA, has the node id as its CN. A second {@code TestPki}
 * is another deployment, whose certificates the first does not trust.
 *
 * <p>Thread-safe; each key store is made once.
 */
final class TestPki {

    static final char[] PASSWORD = "test-only-password".toCharArray();
    private static final String PASS = new String(PASSWORD);

    private final Path directory;
    private final Path caStore;
    private final Path caCertificate;
    private final Path trustStore;
    private final ConcurrentHashMap<String, Path> nodes = new ConcurrentHashMap<>();

    private static TestPki shared;
    private static TestPki sharedRogue;

    /** The deployment most tests share (made once per test JVM: keytool is slow to start). */
    static synchronized TestPki deployment() {
        if (shared == null) {
            shared = new TestPki("deployment-ca");
        }
        return shared;
    }

    /** Another deployment, which {@link #deployment()} does not trust. */
    static synchronized TestPki rogue() {
        if (sharedRogue == null) {
            sharedRogue = new TestPki("rogue-ca");
        }
        return sharedRogue;
    }

    /** A new CA in a fresh temporary directory. */
    TestPki(String caName) {
        try {
            directory = Files.createTempDirectory("etherware-pki-" + caName);
            caStore = directory.resolve("ca.p12");
            caCertificate = directory.resolve("ca.pem");
            trustStore = directory.resolve("trust.p12");
            keytool("-genkeypair", "-alias", "ca", "-keyalg", "EC", "-groupname", "secp256r1", "-dname", "CN=" + caName,
                    "-ext", "bc:c", "-validity", "3", "-keystore", caStore, "-storetype", "PKCS12");
            keytool("-exportcert", "-alias", "ca", "-rfc", "-file", caCertificate, "-keystore", caStore);
            keytool("-importcert", "-noprompt", "-alias", "ca", "-file", caCertificate, "-keystore", trustStore,
                    "-storetype", "PKCS12");
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** Where the stores are: {@code trust.p12} and {@code <nodeId>.p12}, as the README's recipe names them. */
    Path directory() {
        return directory;
    }

    /** The trust store holding this deployment's CA. */
    Path trustStore() {
        return trustStore;
    }

    /** The key store of node {@code nodeId}: its key, and its certificate signed by the CA. */
    Path keyStore(String nodeId) {
        return nodes.computeIfAbsent(nodeId, id -> {
            try {
                Path store = directory.resolve(id + ".p12");
                Path request = directory.resolve(id + ".csr");
                Path signed = directory.resolve(id + ".pem");
                keytool("-genkeypair", "-alias", "node", "-keyalg", "EC", "-groupname", "secp256r1", "-dname", "CN=" + id,
                        "-validity", "3", "-keystore", store, "-storetype", "PKCS12");
                keytool("-certreq", "-alias", "node", "-file", request, "-keystore", store);
                keytool("-gencert", "-alias", "ca", "-infile", request, "-outfile", signed, "-rfc", "-validity", "3",
                        "-ext", "KU=digitalSignature", "-ext", "EKU=serverAuth,clientAuth", "-keystore", caStore);
                keytool("-importcert", "-noprompt", "-alias", "ca", "-file", caCertificate, "-keystore", store);
                keytool("-importcert", "-alias", "node", "-file", signed, "-keystore", store);
                return store;
            } catch (IOException e) {
                throw new UncheckedIOException(e);
            }
        });
    }

    /** A mutual-TLS factory for node {@code nodeId} of this deployment. */
    ConnectionFactory factory(String nodeId) {
        try {
            return ConnectionFactory.tls(keyStore(nodeId), PASSWORD, trustStore, PASSWORD);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** A factory that presents node {@code certificateOf}'s certificate but trusts {@code trusting}'s CA. */
    static ConnectionFactory crossed(TestPki certificateOf, String nodeId, TestPki trusting) {
        try {
            return ConnectionFactory.tls(certificateOf.keyStore(nodeId), PASSWORD, trusting.trustStore, PASSWORD);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    private static void keytool(Object... arguments) throws IOException {
        List<String> command = new ArrayList<>();
        command.add(Path.of(System.getProperty("java.home"), "bin", "keytool").toString());
        for (Object argument : arguments) {
            command.add(argument.toString());
        }
        command.addAll(List.of("-storepass", PASS));
        if (!arguments[0].equals("-exportcert")) {
            command.addAll(List.of("-keypass", PASS));
        }
        Process process = new ProcessBuilder(command).redirectErrorStream(true).start();
        try {
            if (!process.waitFor(60, TimeUnit.SECONDS)) {
                process.destroyForcibly();
                throw new IOException("keytool did not finish in 60 s: " + command);
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IOException("interrupted waiting for keytool", e);
        }
        String output = new String(process.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        if (process.exitValue() != 0) {
            throw new IOException("keytool " + arguments[0] + " failed (" + process.exitValue() + "): " + output);
        }
    }
}
