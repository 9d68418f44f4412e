package io.etherware.deploy;

import java.nio.file.Path;

/**
 * A deployment that cannot start: its message names the file, the line and column, the element,
 * what is wrong and, where there is one, the fix ({@code node1.xml:12:61: <subscription
 * name="controller">: period="15": ...}). Nothing was started when it is thrown, or what was
 * started has been closed again.
 */
public final class DeploymentException extends Exception {

    private static final long serialVersionUID = 1L;

    /** The file, or null for a problem that is not in one. */
    private final transient Path file;
    /** The 1-based line, or 0 if unknown. */
    private final int line;

    /**
     * A problem at a place in a file.
     *
     * @param file    the deployment file
     * @param line    1-based line, or 0 if unknown
     * @param column  1-based column, or 0 if unknown
     * @param message what is wrong, starting with the element (e.g. {@code <network>: ...}), and the fix
     * @param cause   the underlying failure, or null
     */
    public DeploymentException(Path file, int line, int column, String message, Throwable cause) {
        super(place(file, line, column) + message, cause);
        this.file = file;
        this.line = line;
    }

    /**
     * A problem that is not at a place in a file (a resource that failed to open at start).
     *
     * @param message what is wrong, and the fix
     * @param cause   the underlying failure, or null
     */
    public DeploymentException(String message, Throwable cause) {
        this(null, 0, 0, message, cause);
    }

    /**
     * The deployment file the problem is in.
     *
     * @return the file, or null if the problem is not in a file
     */
    public Path file() {
        return file;
    }

    /**
     * The line the problem is on.
     *
     * @return the 1-based line, or 0 if unknown
     */
    public int line() {
        return line;
    }

    private static String place(Path file, int line, int column) {
        if (file == null) {
            return "";
        }
        return file + (line > 0 ? ":" + line + (column > 0 ? ":" + column : "") : "") + ": ";
    }
}
