package io.etherware.examples.output;

import java.nio.file.Files;
import java.nio.file.LinkOption;
import java.nio.file.Path;
import java.util.Optional;
import picocli.CommandLine;
import picocli.CommandLine.ParameterException;

/**
 * Checks a command's output directory before a run, so a path that cannot hold the results is
 * refused at once instead of after minutes of running, when the results would be lost. Touches
 * nothing: the directory is made when the results are written.
 *
 * <p>Stateless and thread-safe.
 */
public final class OutputDirectory {

    private OutputDirectory() {
    }

    /**
     * What keeps {@code dir} from taking the results, or empty if nothing does: it exists and is
     * not a directory, it lies below a file, or the directory that would hold it (or it) is not
     * writable.
     */
    public static Optional<String> problem(Path dir) {
        Path absolute = dir.toAbsolutePath().normalize();
        if (Files.isDirectory(absolute)) {
            return writable(absolute) ? Optional.empty() : Optional.of("the directory is not writable");
        }
        if (Files.exists(absolute)) {
            return Optional.of(Files.isRegularFile(absolute) ? "is a file, not a directory" : "is not a directory");
        }
        if (Files.isSymbolicLink(absolute)) {
            return Optional.of("is a symbolic link to nothing");
        }
        Path ancestor = absolute.getParent();
        while (ancestor != null && !Files.exists(ancestor, LinkOption.NOFOLLOW_LINKS)) {
            ancestor = ancestor.getParent();
        }
        if (ancestor == null) {
            return Optional.of("no part of the path exists");
        }
        if (!Files.isDirectory(ancestor)) {
            return Optional.of("goes through " + ancestor + ", which is "
                    + (Files.isRegularFile(ancestor) ? "a file" : "not a directory"));
        }
        if (!writable(ancestor)) {
            return Optional.of("cannot be made: " + ancestor + " is not writable");
        }
        return Optional.empty();
    }

    /**
     * Refuses {@code dir}, given as {@code option}, if it cannot take the results: a usage error
     * that names the option, the path and what is wrong.
     */
    public static void requireUsable(CommandLine commandLine, String option, Path dir) {
        Optional<String> problem = problem(dir);
        if (problem.isPresent()) {
            throw new ParameterException(commandLine, option + " " + dir + ": " + problem.get()
                    + "; give a directory that can be written (it is made if missing)");
        }
    }

    /** Whether files can be made in {@code dir}: write and search permission (the OS's access check). */
    private static boolean writable(Path dir) {
        return Files.isWritable(dir) && Files.isExecutable(dir);
    }
}
