package io.etherware.rt.platform.internal;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Optional;

/**
 * A cgroup v1 {@code cpu} group of the process's own for its ordinary threads, beside the group
 * its real-time threads stay in. Why: a HotSpot safepoint waits for every Java thread, and where two
 * JVMs' ordinary threads share a CPU, the kernel may run the other JVM's threads for whole slices
 * while this JVM's last thread waits to reach the safepoint, every real-time thread of the JVM
 * stopped meanwhile (docs/REALTIME.md, section 4: up to 8 ms with two JVMs of load threads on one
 * CPU, 0.4 ms with a group per JVM). In a group of its own the JVM's threads are picked one after
 * the other once the group runs.
 *
 * <p>Real-time threads cannot live there on a kernel with RT group scheduling: a new group has
 * {@code cpu.rt_runtime_us=0}, and {@code sched_setscheduler} refuses every real-time policy in it,
 * to root too. So the real-time threads' group ({@link #realtimeGroup()}) is the nearest group, from
 * the process's own up, with a real-time budget, and the ordinary group is made under it.
 *
 * <p>Not thread-safe: {@code CpuPartition} calls it with its lock held. Writes go to the
 * hierarchy's {@code tasks} files, one thread id each; a thread that ended meanwhile is not an error.
 */
public final class OrdinaryCpuGroup {

    private static final List<Path> CPU_HIERARCHIES = List.of(Path.of("/sys/fs/cgroup/cpu"),
            Path.of("/sys/fs/cgroup/cpu,cpuacct"), Path.of("/sys/fs/cgroup/cpuacct,cpu"));

    private final Path hierarchy;
    private final String realtimeGroup;
    private final String ordinaryGroup;

    private OrdinaryCpuGroup(Path hierarchy, String realtimeGroup, String ordinaryGroup) {
        this.hierarchy = hierarchy;
        this.realtimeGroup = realtimeGroup;
        this.ordinaryGroup = ordinaryGroup;
    }

    /** What {@link #create} made, or why it made nothing. */
    public record Outcome(Optional<OrdinaryCpuGroup> group, String reason) {
    }

    /**
     * Makes the group {@code etherware-<pid>} under the nearest group with a real-time budget.
     *
     * @return the group, or the reason there is none: no cgroup v1 cpu hierarchy (cgroup v2 moves
     *         whole processes only), no permission, or a group of that name already there
     */
    public static Outcome create() {
        Optional<Path> mounted = cpuHierarchy();
        if (mounted.isEmpty()) {
            return new Outcome(Optional.empty(), "no cgroup v1 cpu hierarchy under /sys/fs/cgroup");
        }
        Path hierarchy = mounted.get();
        Optional<String> own;
        try {
            own = RealtimeBudget.cpuGroup(Files.readAllLines(Path.of("/proc/self/cgroup")));
        } catch (IOException e) {
            return new Outcome(Optional.empty(), "cannot read /proc/self/cgroup: " + e.getMessage());
        }
        if (own.isEmpty()) {
            return new Outcome(Optional.empty(), "this process is in no cgroup v1 cpu group");
        }
        String realtime = withBudget(hierarchy, own.get());
        String ordinary = (realtime.equals("/") ? "" : realtime) + "/etherware-" + ProcessHandle.current().pid();
        Path dir = dir(hierarchy, ordinary);
        removeStale(dir.getParent());
        try {
            if (!Files.isDirectory(dir)) { // there already if a partition of this JVM could not remove it
                Files.createDirectory(dir);
            }
        } catch (IOException | RuntimeException e) {
            return new Outcome(Optional.empty(), "cannot make cpu group " + dir + ": " + e);
        }
        return new Outcome(Optional.of(new OrdinaryCpuGroup(hierarchy, realtime, ordinary)), "");
    }

    /** {@return where the cgroup v1 hierarchy with the cpu controller is mounted, if it is} */
    static Optional<Path> cpuHierarchy() {
        return CPU_HIERARCHIES.stream().filter(path -> Files.exists(path.resolve("tasks"))).findFirst();
    }

    /** {@return the directory of {@code group}, a path in the hierarchy such as {@code /a/b}} */
    static Path dir(Path hierarchy, String group) {
        return group.equals("/") ? hierarchy : hierarchy.resolve(group.substring(1));
    }

    /** Removes the groups of JVMs that ended without closing their partition (empty ones only). */
    private static void removeStale(Path parent) {
        try (var groups = Files.list(parent)) {
            for (Path group : groups.filter(path -> path.getFileName().toString().matches("etherware-[0-9]+"))
                    .toList()) {
                long pid = Long.parseLong(group.getFileName().toString().substring("etherware-".length()));
                if (ProcessHandle.of(pid).isEmpty()) {
                    try {
                        Files.deleteIfExists(group); // refused while a task is in it: left alone
                    } catch (IOException e) {
                        // still used, or someone else's
                    }
                }
            }
        } catch (IOException | RuntimeException e) {
            // nothing to tidy, or no permission: the new group is made anyway
        }
    }

    /** The nearest group from {@code group} up whose {@code cpu.rt_runtime_us} is not 0 (the root at last). */
    static String withBudget(Path hierarchy, String group) {
        String candidate = group;
        while (!candidate.equals("/") && !candidate.isEmpty()) {
            Path runtime = dir(hierarchy, candidate).resolve("cpu.rt_runtime_us");
            try {
                if (!Files.exists(runtime) || !Files.readString(runtime).strip().equals("0")) {
                    return candidate;
                }
            } catch (IOException e) {
                return candidate;
            }
            candidate = parent(candidate);
        }
        return "/";
    }

    static String parent(String group) {
        int slash = group.lastIndexOf('/');
        return slash <= 0 ? "/" : group.substring(0, slash);
    }

    /** {@return the group the ordinary threads go to, a path in the cpu hierarchy} */
    public String ordinaryGroup() {
        return ordinaryGroup;
    }

    /** {@return the group real-time threads stay in, the nearest one with a real-time budget} */
    public String realtimeGroup() {
        return realtimeGroup;
    }

    /**
     * For a thread that is about to ask for a real-time policy in a JVM without a group of its
     * own: if it was born in another JVM's ordinary group ({@code etherware-<pid>}, inherited by a
     * process that a partitioned JVM started), moves it to the nearest group with a real-time
     * budget, where the request can be granted. A group someone else made is left alone.
     *
     * @return whether it moved the thread
     */
    public static boolean leaveInherited(int tid) {
        try {
            Optional<Path> mounted = cpuHierarchy();
            Optional<String> own = RealtimeBudget.cpuGroup(Files.readAllLines(Path.of("/proc/self/task",
                    Integer.toString(tid), "cgroup")));
            if (mounted.isEmpty() || own.isEmpty() || !own.get().matches(".*/etherware-[0-9]+")) {
                return false;
            }
            String target = withBudget(mounted.get(), own.get());
            if (target.equals(own.get())) {
                return false;
            }
            Files.writeString(dir(mounted.get(), target).resolve("tasks"), Integer.toString(tid));
            return true;
        } catch (IOException | RuntimeException e) {
            return false;
        }
    }

    /** Puts thread {@code tid} in the ordinary group; false if the kernel refused (or it ended). */
    public boolean addOrdinary(int tid) {
        return write(ordinaryGroup, tid);
    }

    /** Puts thread {@code tid} where a real-time policy is allowed; false if the kernel refused (or it ended). */
    public boolean addRealtime(int tid) {
        return write(realtimeGroup, tid);
    }

    /** Whether thread {@code tid} of this process is in the ordinary group now. */
    public boolean holds(int tid) {
        try {
            return RealtimeBudget.cpuGroup(Files.readAllLines(Path.of("/proc/self/task", Integer.toString(tid),
                    "cgroup"))).map(ordinaryGroup::equals).orElse(false);
        } catch (IOException | RuntimeException e) {
            return false;
        }
    }

    /**
     * Moves every thread still in the ordinary group to the real-time threads' group and removes
     * the group.
     *
     * @return how many threads were moved back
     */
    public int close() {
        Path dir = dir(hierarchy, ordinaryGroup);
        int moved = 0;
        try {
            for (String line : Files.readAllLines(dir.resolve("tasks"))) {
                if (!line.isBlank() && write(realtimeGroup, Integer.parseInt(line.strip()))) {
                    moved++;
                }
            }
            Files.deleteIfExists(dir);
        } catch (IOException | RuntimeException e) {
            // A thread that ended or was moved meanwhile; the group goes when its last task leaves.
        }
        return moved;
    }

    private boolean write(String group, int tid) {
        try {
            Files.writeString(dir(hierarchy, group).resolve("tasks"), Integer.toString(tid));
            return true;
        } catch (IOException | RuntimeException e) {
            return false;
        }
    }

    @Override
    public String toString() {
        return "cpu group " + ordinaryGroup + " (real-time threads in " + realtimeGroup + ")";
    }
}
