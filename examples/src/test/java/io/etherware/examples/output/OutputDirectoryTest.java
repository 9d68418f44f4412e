package io.etherware.examples.output;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeFalse;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.Optional;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

class OutputDirectoryTest {

    @TempDir
    Path dir;

    @Test
    void shouldAcceptAWritableDirectoryAndAMissingOneBelowIt() {
        assertEquals(Optional.empty(), OutputDirectory.problem(dir));
        assertEquals(Optional.empty(), OutputDirectory.problem(dir.resolve("a/b/c")));
        assertFalse(Files.exists(dir.resolve("a")), "the check makes nothing");
    }

    @Test
    void shouldRefuseAFile() throws Exception {
        Path file = Files.createFile(dir.resolve("results"));
        assertEquals(Optional.of("is a file, not a directory"), OutputDirectory.problem(file));
    }

    @Test
    void shouldRefuseAPathThroughAFileAndNameTheFile() throws Exception {
        Path file = Files.createFile(dir.resolve("results"));
        assertEquals(Optional.of("goes through " + file + ", which is a file"),
                OutputDirectory.problem(file.resolve("stress/run-1")));
    }

    @Test
    void shouldRefuseADirectoryThatCannotBeWrittenAndOneThatCannotBeMadeThere() throws Exception {
        Path locked = Files.createDirectory(dir.resolve("locked"),
                PosixFilePermissions.asFileAttribute(PosixFilePermissions.fromString("r-xr-xr-x")));
        try {
            assumeFalse(Files.isWritable(locked), "running as root: every directory is writable");
            assertEquals(Optional.of("the directory is not writable"), OutputDirectory.problem(locked));
            Optional<String> below = OutputDirectory.problem(locked.resolve("stress"));
            assertTrue(below.isPresent() && below.get().equals("cannot be made: " + locked + " is not writable"),
                    below.toString());
        } finally {
            Files.setPosixFilePermissions(locked, PosixFilePermissions.fromString("rwxr-xr-x"));
        }
    }
}
