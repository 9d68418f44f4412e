package io.etherware.rt.platform;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.file.Files;
import java.nio.file.Path;

/**
 * A thread's scheduling state read from {@code /proc/self/task/<tid>/stat}: an independent read
 * of what the kernel granted, not through our own FFM calls.
 *
 * @param rtPriority field 40, {@code rt_priority}
 * @param policy     field 41, {@code policy} (0 OTHER, 1 FIFO, 2 RR)
 */
public record OsThreadStat(int rtPriority, int policy) {

    public static OsThreadStat of(int tid) {
        try {
            String stat = Files.readString(Path.of("/proc/self/task/" + tid + "/stat"));
            // Fields after the command name, which is in parentheses and may contain spaces.
            String[] fields = stat.substring(stat.lastIndexOf(')') + 2).strip().split(" ");
            // fields[0] is field 3 (state): field n is fields[n - 3].
            return new OsThreadStat(Integer.parseInt(fields[40 - 3]), Integer.parseInt(fields[41 - 3]));
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** Whether this process holds CAP_SYS_NICE (bit 23 of CapEff), the privilege SCHED_FIFO needs. */
    public static boolean hasCapSysNice() {
        return hasCapability(23);
    }

    public static boolean hasCapability(int bit) {
        try {
            for (String line : Files.readAllLines(Path.of("/proc/self/status"))) {
                if (line.startsWith("CapEff:")) {
                    return (Long.parseUnsignedLong(line.substring(7).strip(), 16) & (1L << bit)) != 0;
                }
            }
            return false;
        } catch (IOException e) {
            return false;
        }
    }
}
