package io.etherware.examples.scenario;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;

/**
 * The CPU time the hypervisor took from this virtual machine (the "steal" column of
 * {@code /proc/stat}, all CPUs), for the failure messages of the scenario tests: a plant that
 * stalled while the machine was frozen says nothing about the middleware.
 */
public final class StolenTime {

    /** Linux reports {@code /proc/stat} in USER_HZ ticks, 100 per second on every supported platform. */
    private static final long MS_PER_TICK = 10;

    private StolenTime() {
    }

    /** Milliseconds stolen since boot, or -1 where {@code /proc/stat} has no steal column. */
    public static long sinceBootMs() {
        try {
            for (String line : Files.readAllLines(Path.of("/proc/stat"))) {
                if (line.startsWith("cpu ")) {
                    String[] fields = line.trim().split("\\s+");
                    return fields.length > 8 ? Long.parseLong(fields[8]) * MS_PER_TICK : -1;
                }
            }
        } catch (IOException | NumberFormatException e) {
            return -1;
        }
        return -1;
    }
}
