package io.etherware.rt.platform;

import java.util.Arrays;
import java.util.BitSet;
import java.util.Objects;

/**
 * A set of CPU indexes for a thread's affinity, or {@link #inherit()}: leave the affinity the
 * thread inherited (usually every CPU the process may use).
 *
 * <p>Immutable and thread-safe. Text form as in {@code taskset -c} and cpuset files:
 * {@code 0-1,3}.
 */
public final class CpuSet {

    /** The largest CPU index glibc's {@code cpu_set_t} can hold, plus one. */
    public static final int MAX_CPUS = 1024;

    private static final CpuSet INHERIT = new CpuSet(new int[0]);

    private final int[] cpus;

    private CpuSet(int[] sortedDistinctCpus) {
        this.cpus = sortedDistinctCpus;
    }

    /**
     * Leave the affinity as inherited.
     *
     * @return the shared empty set that means "no affinity requested"
     */
    public static CpuSet inherit() {
        return INHERIT;
    }

    /**
     * The given CPUs.
     *
     * @param cpus CPU indexes, at least one, each in [0, {@value #MAX_CPUS}); order and repeats do
     *             not matter
     * @return the set, sorted and without repeats
     * @throws IllegalArgumentException when {@code cpus} is empty or an index is out of range
     */
    public static CpuSet of(int... cpus) {
        Objects.requireNonNull(cpus, "cpus");
        if (cpus.length == 0) {
            throw new IllegalArgumentException("cpus=[] must name at least one CPU (use CpuSet.inherit() for no affinity)");
        }
        BitSet bits = new BitSet();
        for (int cpu : cpus) {
            if (cpu < 0 || cpu >= MAX_CPUS) {
                throw new IllegalArgumentException("cpu=" + cpu + " must be in [0, " + MAX_CPUS + ")");
            }
            bits.set(cpu);
        }
        return new CpuSet(bits.stream().toArray());
    }

    /**
     * Parses the {@code taskset -c} form.
     *
     * @param text comma-separated CPU indexes and ascending ranges, e.g. {@code 0-1,3}, each in
     *             [0, {@value #MAX_CPUS}); blank or {@code inherit} for {@link #inherit()}
     * @return the set
     * @throws IllegalArgumentException naming the text and the bad part, when a part is not an
     *                                  index or a range, or is out of range
     */
    public static CpuSet parse(String text) {
        Objects.requireNonNull(text, "text");
        String trimmed = text.strip();
        if (trimmed.isEmpty() || trimmed.equals("inherit")) {
            return INHERIT;
        }
        BitSet bits = new BitSet();
        for (String part : trimmed.split(",", -1)) {
            String range = part.strip();
            try {
                int dash = range.indexOf('-');
                int from = Integer.parseInt(dash < 0 ? range : range.substring(0, dash).strip());
                int to = dash < 0 ? from : Integer.parseInt(range.substring(dash + 1).strip());
                if (from < 0 || to >= MAX_CPUS || from > to) {
                    throw new IllegalArgumentException("cpus='" + text + "': range '" + range
                            + "' must be ascending within [0, " + MAX_CPUS + ")");
                }
                bits.set(from, to + 1);
            } catch (NumberFormatException e) {
                throw new IllegalArgumentException("cpus='" + text + "': '" + range
                        + "' is not a CPU index or a range like 0-3", e);
            }
        }
        return new CpuSet(bits.stream().toArray());
    }

    /**
     * Whether this means "leave the inherited affinity".
     *
     * @return true for {@link #inherit()}
     */
    public boolean isInherit() {
        return cpus.length == 0;
    }

    /**
     * The CPU indexes.
     *
     * @return a new array, ascending without repeats; empty for {@link #inherit()}
     */
    public int[] cpus() {
        return cpus.clone();
    }

    /**
     * Whether the set names a CPU.
     *
     * @param cpu a CPU index
     * @return true when {@code cpu} is one of {@link #cpus()}; always false for {@link #inherit()}
     */
    public boolean contains(int cpu) {
        return Arrays.binarySearch(cpus, cpu) >= 0;
    }

    @Override
    public boolean equals(Object other) {
        return other instanceof CpuSet set && Arrays.equals(cpus, set.cpus);
    }

    @Override
    public int hashCode() {
        return Arrays.hashCode(cpus);
    }

    /** {@code 0-1,3}, or {@code inherit}. */
    @Override
    public String toString() {
        if (cpus.length == 0) {
            return "inherit";
        }
        var text = new StringBuilder();
        int start = 0;
        for (int i = 1; i <= cpus.length; i++) {
            if (i == cpus.length || cpus[i] != cpus[i - 1] + 1) {
                if (!text.isEmpty()) {
                    text.append(',');
                }
                text.append(cpus[start]);
                if (i - 1 > start) {
                    text.append('-').append(cpus[i - 1]);
                }
                start = i;
            }
        }
        return text.toString();
    }
}
