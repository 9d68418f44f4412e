package io.etherware.core.message;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.lang.module.Configuration;
import java.lang.module.ModuleFinder;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Set;
import java.util.spi.ToolProvider;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * Registration refuses, at once, a record in a named module that the codec could not read: the
 * mistake that otherwise fails every remote request that carries it, later.
 */
class ContentsTypesModuleTest {

    @TempDir
    Path dir;

    @Test
    void shouldRefuseARecordWhosePackageIsNeitherExportedNorOpenedAndNameTheFix() throws Exception {
        Module module = compileAndLoad("""
                module app.sensor { }
                """, "app.sensor.internal", "public record Reading(double celsius) { }");
        Class<?> reading = module.getClassLoader().loadClass("app.sensor.internal.Reading");

        var error = assertThrows(IllegalArgumentException.class,
                () -> new ContentsTypes().registerAny("reading", asContents(reading)));

        assertTrue(error.getMessage().contains("app.sensor.internal.Reading cannot be read by the codec"), error.getMessage());
        assertTrue(error.getMessage().contains("'opens app.sensor.internal to io.etherware.core;'"), error.getMessage());
    }

    @Test
    void shouldAcceptARecordWhosePackageIsOpenedToTheCodec() throws Exception {
        Module module = compileAndLoad("""
                module app.sensor { opens app.sensor.internal; }
                """, "app.sensor.internal", "record Reading(double celsius) { }");
        Class<?> reading = module.getClassLoader().loadClass("app.sensor.internal.Reading");

        var types = new ContentsTypes().registerAny("reading", asContents(reading));

        assertSame(reading, types.typeOf("reading"));
    }

    @Test
    void shouldRefuseAPackagePrivateRecordInAnExportedPackageThatIsNotOpened() throws Exception {
        Module module = compileAndLoad("""
                module app.sensor { exports app.sensor.internal; }
                """, "app.sensor.internal", "record Reading(double celsius) { }");
        Class<?> reading = module.getClassLoader().loadClass("app.sensor.internal.Reading");

        var error = assertThrows(IllegalArgumentException.class,
                () -> new ContentsTypes().registerAny("reading", asContents(reading)));

        assertTrue(error.getMessage().contains("the record is not public"), error.getMessage());
        assertEquals(Set.of("empty", "text", "tick"), new ContentsTypes().names());
    }

    @SuppressWarnings("unchecked")
    private static Class<? extends Contents> asContents(Class<?> type) {
        // Only the module check is under test: the record need not implement Contents for it.
        return (Class<? extends Contents>) type;
    }

    /** Compiles a one-record module into the temp directory and defines it in a new layer. */
    private Module compileAndLoad(String moduleInfo, String pkg, String record) throws Exception {
        Path src = dir.resolve("src");
        Path pkgDir = src.resolve(pkg.replace('.', '/'));
        Files.createDirectories(pkgDir);
        Files.writeString(src.resolve("module-info.java"), moduleInfo);
        Files.writeString(pkgDir.resolve("Reading.java"), "package " + pkg + ";\n" + record + "\n");
        Path out = Files.createDirectories(dir.resolve("out"));
        int status = ToolProvider.findFirst("javac").orElseThrow().run(System.out, System.err, "-d", out.toString(),
                src.resolve("module-info.java").toString(), pkgDir.resolve("Reading.java").toString());
        assertEquals(0, status, "the test module compiles");
        Configuration configuration = ModuleLayer.boot().configuration()
                .resolve(ModuleFinder.of(out), ModuleFinder.of(), Set.of("app.sensor"));
        ModuleLayer layer = ModuleLayer.boot().defineModulesWithOneLoader(configuration,
                ClassLoader.getSystemClassLoader());
        return layer.findModule("app.sensor").orElseThrow();
    }
}
