package io.etherware.services.management;

import example.counter.SequenceCounter;
import io.etherware.core.component.Component;
import java.io.IOException;
import java.io.OutputStream;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.net.URI;
import java.net.URISyntaxException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.jar.Attributes;
import java.util.jar.JarEntry;
import java.util.jar.JarOutputStream;
import java.util.jar.Manifest;
import java.util.spi.ToolProvider;
import java.util.stream.Stream;
import org.slf4j.LoggerFactory;

/** Compiles Java sources given as strings and packs the classes into a jar, at test time. */
final class JarBuilder {

    private JarBuilder() {
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
