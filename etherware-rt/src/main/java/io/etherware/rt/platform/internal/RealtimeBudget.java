package io.etherware.rt.platform.internal;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Optional;

/**
 * What stands between a thread and a real-time policy besides RLIMIT_RTPRIO, read from
 * {@code /proc} for the advice of a refused {@code sched_setscheduler}: whether the thread holds
 * CAP_SYS_NICE (root does), and whether its cgroup v1 {@code cpu} group has no real-time budget
 * ({@code cpu.rt_runtime_us} 0, the default of every new group on a kernel with RT group
 * scheduling; a thread is born in its creator's group, and no privilege lifts that refusal).
 * Stateless and thread-safe; the parsing is pure and unit-tested.
 *
 * @param capSysNice   whether the thread's effective capabilities include CAP_SYS_NICE, or empty
 *                     when unknown
 * @param emptyCpuGroup the path of the thread's cgroup v1 cpu group if its
 *                     {@code cpu.rt_runtime_us} is 0, else empty
 */
public record RealtimeBudget(Optional<Boolean> capSysNice, Optional<String> emptyCpuGroup) {

    /** CAP_SYS_NICE's bit in the capability sets (capability.h). */
    static final int CAP_SYS_NICE = 23;
    /** Nothing known: the advice falls back to the privilege and the limit. */
    public static final RealtimeBudget UNKNOWN = new RealtimeBudget(Optional.empty(), Optional.empty());

    /** {@return the calling thread's, from /proc/thread-self; {@link #UNKNOWN} where that cannot be read} */
    public static RealtimeBudget ofCurrentThread() {
        try {
            Optional<Boolean> cap = capSysNice(Files.readAllLines(Path.of("/proc/thread-self/status")));
            Optional<String> group = cpuGroup(Files.readAllLines(Path.of("/proc/thread-self/cgroup")));
            Optional<String> empty = group.filter(RealtimeBudget::hasNoRuntime);
            return new RealtimeBudget(cap, empty);
        } catch (IOException | RuntimeException e) {
            return UNKNOWN;
        }
    }

    /** The {@code CapEff} line of a {@code status} file, as whether it holds CAP_SYS_NICE. */
    static Optional<Boolean> capSysNice(List<String> statusLines) {
        for (String line : statusLines) {
            if (line.startsWith("CapEff:")) {
                long effective = Long.parseUnsignedLong(line.substring("CapEff:".length()).strip(), 16);
                return Optional.of((effective & (1L << CAP_SYS_NICE)) != 0);
            }
        }
        return Optional.empty();
    }

    /** The path of the cgroup v1 hierarchy with the {@code cpu} controller in a {@code cgroup} file. */
    static Optional<String> cpuGroup(List<String> cgroupLines) {
        for (String line : cgroupLines) {
            String[] fields = line.split(":", 3);
            if (fields.length == 3 && List.of(fields[1].split(",")).contains("cpu")) {
                return Optional.of(fields[2]);
            }
        }
        return Optional.empty();
    }

    private static boolean hasNoRuntime(String group) {
        Optional<Path> hierarchy = OrdinaryCpuGroup.cpuHierarchy();
        if (hierarchy.isEmpty()) {
            return false;
        }
        Path runtime = OrdinaryCpuGroup.dir(hierarchy.get(), group).resolve("cpu.rt_runtime_us");
        try {
            return Files.isReadable(runtime) && Files.readString(runtime).strip().equals("0");
        } catch (IOException e) {
            return false;
        }
    }
}
