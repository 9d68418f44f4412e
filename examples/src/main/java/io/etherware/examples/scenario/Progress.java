package io.etherware.examples.scenario;

import java.io.PrintStream;
import java.util.Locale;
import java.util.Objects;

/**
 * The line a scenario prints while it runs: elapsed / total, the pendulum's θ2 and the deadline
 * misses so far. On a terminal it rewrites one line in place; otherwise (a pipe, a build log) it
 * prints a line every few seconds.
 *
 * <p>Not thread-safe: one thread updates it.
 */
public final class Progress {

    private static final double LOG_EVERY_S = 5.0;

    private final String label;
    private final double totalS;
    private final PrintStream out;
    private final boolean terminal;
    private double lastPrintedS = Double.NEGATIVE_INFINITY;

    /** Progress of the run {@code label}, {@code totalS} long, printed to {@code out}. */
    public Progress(String label, double totalS, PrintStream out, boolean terminal) {
        this.label = Objects.requireNonNull(label, "label");
        this.totalS = totalS;
        this.out = Objects.requireNonNull(out, "out");
        this.terminal = terminal;
    }

    /** Progress on standard error, rewriting in place when it is a terminal. */
    public static Progress onStandardError(String label, double totalS) {
        var console = System.console();
        return new Progress(label, totalS, System.err, console != null && console.isTerminal());
    }

    /** Reports the state at {@code elapsedS}. */
    public void update(double elapsedS, double theta2Rad, long misses) {
        String line = String.format(Locale.ROOT, "%-20s %5.1f / %.1f s   θ2 %+7.4f rad   misses %d", label,
                Math.min(elapsedS, totalS), totalS, theta2Rad, misses);
        if (terminal) {
            out.print("\r" + line + "   ");
            out.flush();
        } else if (elapsedS - lastPrintedS >= LOG_EVERY_S) {
            lastPrintedS = elapsedS;
            out.println(line);
        }
    }

    /** Prints {@code text} as a line of its own (on a terminal, over the progress line). */
    public void note(String text) {
        out.println(terminal ? "\r" + text : text);
        out.flush();
    }

    /** Ends the progress line with the final state. */
    public void finish(double elapsedS, double theta2Rad, long misses) {
        lastPrintedS = Double.NEGATIVE_INFINITY;
        update(elapsedS, theta2Rad, misses);
        if (terminal) {
            out.println();
        }
    }
}
