package io.etherware.rt.platform.internal;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Optional;
import java.util.regex.Pattern;

/**
 * A cgroup v1 {@code cpu} group of the process's own for its ordinary threads, beside the group
 * its real-time threads stay in. Why: a HotSpot safepoint waits for every Java thread, and where two
 * JVMs' ordinary threads share a CPU, the kernel may run the other JVM's threads for whole slices
 * while this JVM's last thread waits to reach the safepoint, every real-time thread of the JVM
 * stopped meanwhile (docs/REALTIME.md, section 4: up to 8 ms with two JVMs of load threads on one
 * CPU, 0.4 ms with a group per JVM). In a group of its own the JVM's threads are picked one after
 * the other once the group runs. The group weighs as one task against the tasks of its parent.
 *
 * <p>Real-time threads cannot live there on a kernel with RT group scheduling: a new group has
 * {@code cpu.rt_runtime_us=0}, and {@code sched_setscheduler} refuses every real-time policy in it,
 * to root too. So the real-time threads stay in the process's own group ({@link #realtimeGroup()};
 * above any {@code etherware-<pid>} group it was born in, a partitioned parent JVM's), and the
 * ordinary group is made under it. Where the process's own group has no real-time budget, no group
 * is made: climbing above it would take the JVM out of a group an administrator chose.
 *
 * <p>Not thread-safe: {@code CpuPartition} calls it with its lock held. A thread moves by a write of
 * its id to a group's {@code tasks} file (of 0 for the calling thread, which spares the kernel's
 * global lock); a thread that ended meanwhile is not an error.
 */
public final class OrdinaryCpuGroup {

    private static final List<Path> CPU_HIERARCHIES = List.of(Path.of("/sys/fs/cgroup/cpu"),
            Path.of("/sys/fs/cgroup/cpu,cpuacct"), Path.of("/sys/fs/cgroup/cpuacct,cpu"));
    /** Our groups' names: {@code etherware-<pid>}. */
    private static final Pattern OURS = Pattern.compile("etherware-[0-9]{1,18}");
    /** How often {@link #close()} empties the group and tries to remove it before it gives up. */
    private static final int CLOSE_ATTEMPTS = 10;

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
     * Makes the group {@code etherware-<pid>} under the process's own cpu group (above any of ours
     * it inherited), or reuses it if a partition of this JVM could not remove it.
     *
     * @return the group, or the reason there is none: no cgroup v1 cpu hierarchy (cgroup v2 moves
     *         whole processes only), no permission, or a process group without a real-time budget
     */
    public static Outcome create() {
        Optional<Path> mounted = cpuHierarchy();
        if (mounted.isEmpty()) {
            return new Outcome(Optional.empty(), "no cgroup v1 cpu hierarchy under /sys/fs/cgroup");
        }
        Path hierarchy = mounted.get();
        Optional<String> own = groupOf("thread-self");
        if (own.isEmpty()) {
            return new Outcome(Optional.empty(), "this process is in no cgroup v1 cpu group");
        }
        Optional<String> home = realtimeHome(hierarchy, own.get());
        if (home.isEmpty()) {
            return new Outcome(Optional.empty(), "the process's cpu group " + outOfOurs(own.get())
                    + " has no real-time budget (cpu.rt_runtime_us=0)");
        }
        String realtime = home.get();
        String ordinary = (realtime.equals("/") ? "" : realtime) + "/etherware-" + ProcessHandle.current().pid();
        Path dir = dir(hierarchy, ordinary);
        removeStale(dir.getParent());
        try {
            if (!Files.isDirectory(dir)) {
                Files.createDirectory(dir);
            }
        } catch (IOException | RuntimeException e) {
            return new Outcome(Optional.empty(), "cannot make cpu group " + dir + ": " + e);
        }
        return new Outcome(Optional.of(new OrdinaryCpuGroup(hierarchy, realtime, ordinary)), "");
    }

    /** {@return where the cgroup v1 hierarchy with the cpu controller is mounted, if it is} */
    public static Optional<Path> cpuHierarchy() {
        return CPU_HIERARCHIES.stream().filter(path -> Files.exists(path.resolve("tasks"))).findFirst();
    }

    /**
     * The group real-time threads of a process in {@code group} belong in: {@code group} above any
     * {@code etherware-<pid>} groups (ours, inherited from a partitioned parent), if real-time
     * threads can be granted there (no {@code cpu.rt_runtime_us}, or not 0).
     *
     * @return the group, or empty where real-time threads would be refused in it
     */
    public static Optional<String> realtimeHome(Path hierarchy, String group) {
        String candidate = outOfOurs(group);
        Path runtime = dir(hierarchy, candidate).resolve("cpu.rt_runtime_us");
        try {
            if (Files.exists(runtime) && Files.readString(runtime).strip().equals("0")) {
                return Optional.empty();
            }
        } catch (IOException | RuntimeException e) {
            return Optional.empty();
        }
        return Optional.of(candidate);
    }

    static String outOfOurs(String group) {
        String candidate = group;
        while (OURS.matcher(candidate.substring(candidate.lastIndexOf('/') + 1)).matches()) {
            candidate = parent(candidate);
        }
        return candidate;
    }

    static String parent(String group) {
        int slash = group.lastIndexOf('/');
        return slash <= 0 ? "/" : group.substring(0, slash);
    }

    /** {@return the directory of {@code group}, a path in the hierarchy such as {@code /a/b}} */
    static Path dir(Path hierarchy, String group) {
        return group.equals("/") ? hierarchy : hierarchy.resolve(group.substring(1));
    }

    /** The cpu group of {@code task} ({@code thread-self}, or {@code self/task/<tid>}), if it has one. */
    static Optional<String> groupOf(String task) {
        try {
            return RealtimeBudget.cpuGroup(Files.readAllLines(Path.of("/proc", task, "cgroup")));
        } catch (IOException | RuntimeException e) {
            return Optional.empty();
        }
    }

    /** Removes the groups of JVMs that ended without closing their partition (empty ones only). */
    private static void removeStale(Path parent) {
        List<Path> groups;
        try (var listing = Files.list(parent)) {
            groups = listing.filter(path -> OURS.matcher(path.getFileName().toString()).matches()).toList();
        } catch (IOException | RuntimeException e) {
            return; // nothing to tidy, or no permission: the new group is made anyway
        }
        for (Path group : groups) {
            try {
                long pid = Long.parseLong(group.getFileName().toString().substring("etherware-".length()));
                if (ProcessHandle.of(pid).isEmpty()) {
                    Files.deleteIfExists(group); // refused while a task is in it: left alone
                }
            } catch (IOException | RuntimeException e) {
                // still used, or someone else's
            }
        }
    }

    /**
     * For the calling thread, about to ask for a policy in a JVM without a group of its own: if it
     * is in one of our groups (inherited by a process that a partitioned JVM started), moves it to
     * the group real-time threads belong in, where a real-time policy can be granted or lent to it.
     * A group someone else made is left alone.
     *
     * @return whether it moved the thread
     */
    public static boolean leaveInherited() {
        Optional<String> own = groupOf("thread-self");
        Optional<Path> mounted = cpuHierarchy();
        if (own.isEmpty() || mounted.isEmpty() || outOfOurs(own.get()).equals(own.get())) {
            return false;
        }
        Optional<String> home = realtimeHome(mounted.get(), own.get());
        return home.isPresent() && write(mounted.get(), home.get(), 0);
    }

    /** {@return the group the ordinary threads go to, a path in the cpu hierarchy} */
    public String ordinaryGroup() {
        return ordinaryGroup;
    }

    /** {@return the group real-time threads stay in} */
    public String realtimeGroup() {
        return realtimeGroup;
    }

    /** Puts thread {@code tid} in the ordinary group; false if the kernel refused (or it ended). */
    public boolean addOrdinary(int tid) {
        return write(hierarchy, ordinaryGroup, tid);
    }

    /**
     * Takes the calling thread out of the ordinary group, or out of one of ours it was born in, to
     * where a real-time policy can be granted or lent; nothing if it is in neither.
     *
     * @return whether it moved the thread
     */
    public boolean releaseCurrent() {
        Optional<String> own = groupOf("thread-self");
        if (own.isEmpty() || outOfOurs(own.get()).equals(own.get())) {
            return false;
        }
        return write(hierarchy, realtimeGroup, 0);
    }

    /**
     * Moves every thread still in the ordinary group to the real-time threads' group and removes
     * the group; again, a few times, if a thread was born in it meanwhile.
     *
     * @return how many threads were moved, and whether the group is gone
     */
    public Closed close() {
        Path dir = dir(hierarchy, ordinaryGroup);
        int moved = 0;
        for (int attempt = 0; attempt < CLOSE_ATTEMPTS; attempt++) {
            try {
                for (String line : Files.readAllLines(dir.resolve("tasks"))) {
                    if (!line.isBlank() && write(hierarchy, realtimeGroup, Integer.parseInt(line.strip()))) {
                        moved++;
                    }
                }
                Files.deleteIfExists(dir);
                return new Closed(moved, true);
            } catch (IOException | RuntimeException e) {
                // EBUSY: a thread was born in it since the read, or ended meanwhile; read again
            }
        }
        return new Closed(moved, !Files.exists(dir));
    }

    /** What {@link #close()} did. */
    public record Closed(int threadsMoved, boolean removed) {
    }

    private static boolean write(Path hierarchy, String group, int tid) {
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
