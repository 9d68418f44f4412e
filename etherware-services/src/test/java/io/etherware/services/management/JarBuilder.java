package io.etherware.services.management;

import example.counter.SequenceCounter;
import io.etherware.core.component.Component;
import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.net.URI;
import java.net.URISyntaxException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.security.GeneralSecurityException;
import java.security.KeyStore;
import java.security.cert.X509Certificate;
import java.util.ArrayList;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.jar.Attributes;
import java.util.jar.JarEntry;
import java.util.jar.JarOutputStream;
import java.util.jar.Manifest;
import java.util.concurrent.TimeUnit;
import java.util.spi.ToolProvider;
import java.util.stream.Stream;
import java.util.zip.ZipEntry;
import java.util.zip.ZipFile;
import java.util.zip.ZipOutputStream;
import org.slf4j.LoggerFactory;

/**
 * Compiles Java sources given as strings and packs the classes into a jar, and signs jars, at test
 * time: keys are made by the JDK's own {@code keytool} and jars signed by its {@code jarsigner}
 * (from {@code java.home}), into temporary directories; no private key is kept in the repository.
 */
final class JarBuilder {

    /** The password of every test key store. */
    static final String PASSWORD = "test-password";
    private static final long TOOL_TIMEOUT_S = 120;
    private static SigningKey testKey;

    private JarBuilder() {
    }

    /**
     * A key pair in a PKCS12 key store and its certificate.
     *
     * @param keyStore    the key store holding the private key under {@code alias}
     * @param certificate the key's certificate (self-signed, or issued by a test CA)
     */
    record SigningKey(Path keyStore, String alias, X509Certificate certificate) {
    }

    /** The key every test that only needs "a trusted signer" shares: made once per test JVM. */
    static synchronized SigningKey testKey() throws IOException {
        if (testKey == null) {
            Path directory = Files.createTempDirectory("etherware-test-keys");
            testKey = newKey(directory, "etherware-test-signer", 0, 30);
        }
        return testKey;
    }

    /** {@link #build} and sign with {@link #testKey()}. */
    static Path buildSigned(Path jar, Map<String, String> sources) throws IOException {
        return sign(build(jar, sources), testKey());
    }

    /**
     * A new self-signed key, valid from {@code startDays} (negative: in the past) for
     * {@code validityDays}, in {@code directory/alias.p12}.
     */
    static SigningKey newKey(Path directory, String alias, int startDays, int validityDays) throws IOException {
        Path store = directory.resolve(alias + ".p12");
        List<String> command = new ArrayList<>(List.of(tool("keytool"), "-genkeypair", "-keyalg", "EC", "-groupname",
                "secp256r1", "-alias", alias, "-dname", "CN=" + alias + ",O=Etherware tests", "-validity",
                Integer.toString(validityDays), "-keystore", store.toString(), "-storetype", "PKCS12", "-storepass",
                PASSWORD, "-keypass", PASSWORD, "-ext", "bc:c"));
        if (startDays != 0) {
            command.addAll(List.of("-startdate", (startDays > 0 ? "+" : "") + startDays + "d"));
        }
        run(command);
        return new SigningKey(store, alias, certificateOf(store, alias));
    }

    /** A new key whose certificate {@code issuer} issued (keytool -certreq, -gencert, -importcert). */
    static SigningKey newKeyIssuedBy(Path directory, String alias, SigningKey issuer) throws IOException {
        SigningKey own = newKey(directory, alias, 0, 30);
        Path request = directory.resolve(alias + ".csr");
        Path issued = directory.resolve(alias + ".cer");
        Path issuerCertificate = exportCertificate(issuer, directory.resolve(issuer.alias() + ".cer"));
        run(List.of(tool("keytool"), "-certreq", "-alias", alias, "-keystore", own.keyStore().toString(),
                "-storepass", PASSWORD, "-file", request.toString()));
        run(List.of(tool("keytool"), "-gencert", "-alias", issuer.alias(), "-keystore", issuer.keyStore().toString(),
                "-storepass", PASSWORD, "-infile", request.toString(), "-outfile", issued.toString(), "-validity",
                "30"));
        run(List.of(tool("keytool"), "-importcert", "-noprompt", "-alias", issuer.alias(), "-keystore",
                own.keyStore().toString(), "-storepass", PASSWORD, "-file", issuerCertificate.toString()));
        run(List.of(tool("keytool"), "-importcert", "-alias", alias, "-keystore", own.keyStore().toString(),
                "-storepass", PASSWORD, "-file", issued.toString()));
        return new SigningKey(own.keyStore(), alias, certificateOf(own.keyStore(), alias));
    }

    /** Writes {@code key}'s certificate to {@code file} (keytool -exportcert). */
    static Path exportCertificate(SigningKey key, Path file) throws IOException {
        run(List.of(tool("keytool"), "-exportcert", "-alias", key.alias(), "-keystore", key.keyStore().toString(),
                "-storepass", PASSWORD, "-file", file.toString()));
        return file;
    }

    /** A PKCS12 trust store holding {@code key}'s certificate (keytool -importcert), as a deployment makes one. */
    static Path trustStore(Path file, SigningKey key) throws IOException {
        Path certificate = exportCertificate(key, file.resolveSibling(key.alias() + "-trusted.cer"));
        run(List.of(tool("keytool"), "-importcert", "-noprompt", "-alias", key.alias(), "-file",
                certificate.toString(), "-keystore", file.toString(), "-storetype", "PKCS12", "-storepass", PASSWORD));
        return file;
    }

    /** Signs {@code jar} in place with {@code key} (jarsigner). */
    static Path sign(Path jar, SigningKey key) throws IOException {
        run(List.of(tool("jarsigner"), "-keystore", key.keyStore().toString(), "-storepass", PASSWORD, "-keypass",
                PASSWORD, jar.toString(), key.alias()));
        return jar;
    }

    /** Rewrites {@code jar} with entry {@code name}'s bytes replaced by {@code bytes} (added if absent). */
    static Path replaceEntry(Path jar, String name, byte[] bytes) throws IOException {
        Path rewritten = jar.resolveSibling(jar.getFileName() + ".tmp");
        boolean replaced = false;
        try (var in = new ZipFile(jar.toFile()); var out = new ZipOutputStream(Files.newOutputStream(rewritten))) {
            for (ZipEntry entry : java.util.Collections.list(in.entries())) {
                out.putNextEntry(new ZipEntry(entry.getName()));
                if (entry.getName().equals(name)) {
                    out.write(bytes);
                    replaced = true;
                } else {
                    try (InputStream data = in.getInputStream(entry)) {
                        data.transferTo(out);
                    }
                }
                out.closeEntry();
            }
            if (!replaced) {
                out.putNextEntry(new ZipEntry(name));
                out.write(bytes);
                out.closeEntry();
            }
        }
        Files.move(rewritten, jar, StandardCopyOption.REPLACE_EXISTING);
        return jar;
    }

    /** The bytes of entry {@code name} of {@code jar}. */
    static byte[] entry(Path jar, String name) throws IOException {
        try (var in = new ZipFile(jar.toFile())) {
            ZipEntry entry = in.getEntry(name);
            if (entry == null) {
                throw new IllegalArgumentException(jar + " has no entry " + name);
            }
            try (InputStream data = in.getInputStream(entry)) {
                return data.readAllBytes();
            }
        }
    }

    private static X509Certificate certificateOf(Path store, String alias) throws IOException {
        try (InputStream in = Files.newInputStream(store)) {
            KeyStore keyStore = KeyStore.getInstance("PKCS12");
            keyStore.load(in, PASSWORD.toCharArray());
            return (X509Certificate) keyStore.getCertificate(alias);
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("cannot read " + store + ": " + e, e);
        }
    }

    private static String tool(String name) {
        return Path.of(System.getProperty("java.home"), "bin", name).toString();
    }

    /** Runs a JDK tool; its output goes into the exception if it fails. */
    private static void run(List<String> command) throws IOException {
        Process process = new ProcessBuilder(command).redirectErrorStream(true).start();
        process.getOutputStream().close();
        String output = new String(process.getInputStream().readAllBytes(), java.nio.charset.StandardCharsets.UTF_8);
        try {
            if (!process.waitFor(TOOL_TIMEOUT_S, TimeUnit.SECONDS)) {
                process.destroyForcibly();
                throw new IllegalStateException(command + " did not finish within " + TOOL_TIMEOUT_S + " s:\n" + output);
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            process.destroyForcibly();
            throw new IllegalStateException("interrupted running " + command, e);
        }
        if (process.exitValue() != 0) {
            throw new IllegalStateException(String.join(" ", command) + " failed (" + process.exitValue() + "):\n"
                    + output);
        }
    }

    /**
     * Compiles {@code sources} (binary class name to source text) against this JVM's class path and
     * writes the classes into {@code jar}. Uses the {@code javac} tool provider of {@code java.base},
     * so the module under test needs no access to {@code java.compiler}.
     */
    static Path build(Path jar, Map<String, String> sources) throws IOException {
        ToolProvider javac = ToolProvider.findFirst("javac").orElseThrow(
                () -> new IllegalStateException("no javac in this runtime: run the tests on a JDK"));
        Path work = Files.createTempDirectory("etherware-jar");
        Path classes = Files.createDirectories(work.resolve("classes"));
        List<String> arguments = new ArrayList<>(List.of("-classpath", classPath(), "-d", classes.toString(),
                "-proc:none", "-implicit:none", "--release", Integer.toString(Runtime.version().feature())));
        for (Map.Entry<String, String> source : sources.entrySet()) {
            Path file = work.resolve("src").resolve(source.getKey().replace('.', '/') + ".java");
            Files.createDirectories(file.getParent());
            Files.writeString(file, source.getValue());
            arguments.add(file.toString());
        }
        var output = new StringWriter();
        try (var out = new PrintWriter(output)) {
            int status = javac.run(out, out, arguments.toArray(String[]::new));
            if (status != 0) {
                throw new IllegalStateException("compiling " + sources.keySet() + " failed:\n" + output);
            }
        }
        try (OutputStream file = Files.newOutputStream(jar); var out = new JarOutputStream(file, manifest());
             Stream<Path> walk = Files.walk(classes)) {
            for (Path path : walk.filter(Files::isRegularFile).sorted().toList()) {
                out.putNextEntry(new JarEntry(classes.relativize(path).toString().replace('\\', '/')));
                out.write(Files.readAllBytes(path));
                out.closeEntry();
            }
        } finally {
            deleteTree(work);
        }
        return jar;
    }

    private static void deleteTree(Path root) throws IOException {
        try (Stream<Path> walk = Files.walk(root)) {
            for (Path path : walk.sorted(java.util.Comparator.reverseOrder()).toList()) {
                Files.delete(path);
            }
        }
    }

    private static Manifest manifest() {
        var manifest = new Manifest();
        manifest.getMainAttributes().put(Attributes.Name.MANIFEST_VERSION, "1.0");
        return manifest;
    }

    /** The JVM's class path plus the places of the types the sources use (surefire may hide them in a manifest jar). */
    private static String classPath() {
        Set<String> entries = new LinkedHashSet<>(List.of(System.getProperty("java.class.path").split(
                java.io.File.pathSeparator)));
        for (Class<?> type : List.of(Component.class, SequenceCounter.class, LoggerFactory.class)) {
            entries.add(locationOf(type));
        }
        return String.join(java.io.File.pathSeparator, entries);
    }

    private static String locationOf(Class<?> type) {
        try {
            URI location = type.getProtectionDomain().getCodeSource().getLocation().toURI();
            return Path.of(location).toString();
        } catch (URISyntaxException e) {
            throw new IllegalStateException(e);
        }
    }
}
