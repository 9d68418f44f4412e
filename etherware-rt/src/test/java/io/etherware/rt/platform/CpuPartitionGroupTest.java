package io.etherware.rt.platform;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.rt.platform.internal.LinuxNative;
import io.etherware.rt.platform.internal.OrdinaryCpuGroup;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Arrays;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;
import org.junit.jupiter.api.Assumptions;
import org.junit.jupiter.api.Test;

/**
 * The partition's cpu cgroup for ordinary threads ({@link CpuPartition#ordinaryCpuGroup()}). Needs
 * Linux, two CPUs, and a cgroup v1 cpu hierarchy the process may write (root); skipped otherwise,
 * saying why. Runs as root in CI, where every test here runs.
 */
class CpuPartitionGroupTest {

    @Test
    void shouldPutOrdinaryThreadsInTheGroupAndGrantRealtimeToThreadsBornThere() throws Exception {
        CpuSet realtime = realtimeCpuOrSkip();
        var platform = Platform.current();
        // A thread the platform configured before the partition opened (an ordinary dispatcher,
        // say): the partition must leave it out of the group, where a lent priority would be refused.
        var configuredEarlier = new CompletableFuture<String>();
        var release = new CountDownLatch(1);
        Thread earlier = Thread.ofPlatform().start(() -> {
            platform.configureCurrentThreadWithoutWarning(ThreadPolicy.NON_REALTIME, CpuSet.inherit());
            configuredEarlier.complete("configured");
            awaitQuietly(release);
            configuredEarlier.obtrudeValue(cpuGroupOf("thread-self"));
        });
        configuredEarlier.get();
        String group;
        ThreadGrant bornThere;
        String[] after = new String[1];
        try (CpuPartition partition = platform.partitionCpus(realtime)) {
            group = groupOrSkip(partition);
            release.countDown();
            earlier.join();
            assertNotEquals(group, configuredEarlier.get(), "configured before the partition: left out");
            assertEquals(group, cpuGroupOf("thread-self"), "the opener, an ordinary thread, is in the group");
            // A thread born in the group asks for a real-time policy: the group has no real-time
            // budget, so the platform moves it out first, or the kernel refuses (EPERM).
            bornThere = PlatformTest.onFreshThread(() -> {
                ThreadGrant grant = platform.configureCurrentThreadWithoutWarning(ThreadPolicy.fifo(1),
                        CpuSet.inherit());
                after[0] = cpuGroupOf("thread-self");
                return grant;
            });
        }
        assertTrue(bornThere.refusals().isEmpty(), bornThere.toLine());
        assertTrue(bornThere.granted().isRealtime(), bornThere.toLine());
        assertNotEquals(group, after[0], "moved out of the ordinary group");
        assertNotEquals(group, cpuGroupOf("thread-self"), "the opener is out of the group after the close");
        assertFalse(Files.exists(dir(group)), "the group is gone with the partition");
    }

    @Test
    void shouldGroupAnOrdinaryThreadBornLaterOutsideTheGroupAtTheKeepersNextSweep() throws Exception {
        CpuSet realtime = realtimeCpuOrSkip();
        var platform = Platform.current();
        try (CpuPartition partition = platform.partitionCpus(realtime)) {
            String group = groupOrSkip(partition);
            // Started by a thread the platform configured (outside the group), as a pool thread
            // started from a dispatcher is: born outside, the keeper puts it in within a sweep or two.
            String seen = PlatformTest.onFreshThread(() -> {
                platform.configureCurrentThreadWithoutWarning(ThreadPolicy.NON_REALTIME, CpuSet.inherit());
                var late = new AtomicReference<String>();
                Thread child = Thread.ofPlatform().start(() -> {
                    long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(5);
                    String now = cpuGroupOf("thread-self");
                    while (!now.equals(group) && System.nanoTime() < deadlineNs) {
                        sleepMs(50);
                        now = cpuGroupOf("thread-self");
                    }
                    late.set(now);
                });
                joinQuietly(child);
                return late.get();
            });
            assertEquals(group, seen, "an ordinary thread born outside the group, after the keeper's sweeps");
        }
    }

    @Test
    void shouldLeaveAGroupInheritedFromAPartitionedParentWhenConfiguredWithoutAPartition() throws Exception {
        realtimeCpuOrSkip();
        Path hierarchy = writableHierarchyOrSkip();
        // What a JVM started by a partitioned one is born in: that JVM's group, named as ours are.
        long deadPid = deadPid();
        Path inherited = hierarchy.resolve("etherware-" + deadPid);
        Files.createDirectories(inherited);
        try {
            String[] groups = PlatformTest.onFreshThread(() -> {
                write(inherited.resolve("tasks"), "0");
                String before = cpuGroupOf("thread-self");
                ThreadGrant grant = Platform.current().configureCurrentThreadWithoutWarning(ThreadPolicy.fifo(1),
                        CpuSet.inherit());
                return new String[] {before, cpuGroupOf("thread-self"), grant.toLine()};
            });
            assertEquals("/etherware-" + deadPid, groups[0], "born in the parent's group");
            assertEquals("/", groups[1], "out of it at the configuration: " + groups[2]);
            assertFalse(groups[2].contains("refused"), groups[2]);
        } finally {
            Files.deleteIfExists(inherited);
        }
    }

    @Test
    void shouldRemoveTheEmptyGroupOfAJvmThatDiedWhenAPartitionOpens() throws Exception {
        CpuSet realtime = realtimeCpuOrSkip();
        Path hierarchy = writableHierarchyOrSkip();
        Path stale = hierarchy.resolve("etherware-" + deadPid());
        Files.createDirectories(stale);
        try (CpuPartition partition = Platform.current().partitionCpus(realtime)) {
            groupOrSkip(partition);
            assertFalse(Files.exists(stale), "a dead JVM's empty group is removed");
        } finally {
            Files.deleteIfExists(stale);
        }
    }

    // ---- helpers ----

    private static CpuSet realtimeCpuOrSkip() {
        Assumptions.assumeTrue(LinuxNative.isAvailable(), "Linux with native access only");
        int[] allowed = LinuxNative.getAffinity(0);
        Assumptions.assumeTrue(allowed != null && allowed.length >= 2, "a partition needs two CPUs");
        Assumptions.assumeTrue(Platform.current().cpuPartition().isEmpty(), "another partition is open");
        return CpuSet.of(allowed[allowed.length - 1]);
    }

    private static Path writableHierarchyOrSkip() {
        var hierarchy = OrdinaryCpuGroup.cpuHierarchy();
        Assumptions.assumeTrue(hierarchy.isPresent() && Files.isWritable(hierarchy.get()),
                "no cgroup v1 cpu hierarchy this process may write");
        Assumptions.assumeTrue("/".equals(cpuGroupOf("self")), "the process is not in the root cpu group");
        return hierarchy.get();
    }

    /** The partition's group; skips only where no group can be made here, fails where one should have been. */
    private static String groupOrSkip(CpuPartition partition) {
        var hierarchy = OrdinaryCpuGroup.cpuHierarchy();
        boolean possible = hierarchy.isPresent() && Files.isWritable(hierarchy.get())
                && OrdinaryCpuGroup.realtimeHome(hierarchy.get(), cpuGroupOf("self")).isPresent();
        Assumptions.assumeTrue(possible || partition.ordinaryCpuGroup().isPresent(),
                () -> "no writable cgroup v1 cpu hierarchy here: " + partition.describe());
        assertTrue(partition.ordinaryCpuGroup().isPresent(), partition.describe());
        return partition.ordinaryCpuGroup().get();
    }

    private static Path dir(String group) {
        return OrdinaryCpuGroup.cpuHierarchy().orElseThrow().resolve(group.substring(1));
    }

    /** A pid no process has now (the group name of a JVM that died). */
    private static long deadPid() {
        long pid = 4_000_000_000L + ProcessHandle.current().pid();
        assertTrue(ProcessHandle.of(pid).isEmpty());
        return pid;
    }

    static String cpuGroupOf(String task) {
        try {
            for (String line : Files.readAllLines(Path.of("/proc", task, "cgroup"))) {
                String[] fields = line.split(":", 3);
                if (fields.length == 3 && Arrays.asList(fields[1].split(",")).contains("cpu")) {
                    return fields[2];
                }
            }
            return "";
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    private static void write(Path file, String text) {
        try {
            Files.writeString(file, text);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    private static void awaitQuietly(CountDownLatch latch) {
        try {
            latch.await();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    private static void joinQuietly(Thread thread) {
        try {
            thread.join();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    private static void sleepMs(long ms) {
        try {
            Thread.sleep(ms);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

}
