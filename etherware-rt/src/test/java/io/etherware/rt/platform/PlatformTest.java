package io.etherware.rt.platform;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.rt.platform.internal.RefusalWarnings;
import java.util.List;
import java.util.concurrent.atomic.AtomicReference;
import java.util.function.Supplier;
import org.junit.jupiter.api.Test;

/**
 * Real OS calls. Each request runs on a fresh thread that ends right after, so no test thread is
 * left at a real-time priority; no thread here spins.
 */
class PlatformTest {

    @Test
    void shouldGrantSchedFifoAsReadBackFromTheOsWhenPrivilegedElseRefuseWithEperm() throws Exception {
        var platform = new Platform(new RefusalWarnings());
        var result = onFreshThread(() -> {
            ThreadGrant grant = platform.configureCurrentThread(ThreadPolicy.fifo(10), CpuSet.inherit());
            return new Object[] {grant, OsThreadStat.of(grant.osThreadId())};
        });
        ThreadGrant grant = (ThreadGrant) result[0];
        OsThreadStat proc = (OsThreadStat) result[1];
        if (platform.isAvailable() && OsThreadStat.hasCapSysNice()) {
            assertEquals(ThreadPolicy.fifo(10), grant.granted(), grant.toLine());
            assertEquals(new OsThreadStat(10, 1), proc, "what /proc says the kernel granted");
            assertTrue(grant.refusals().isEmpty(), grant.toLine());
            assertEquals(0, platform.warnings().warningsLogged());
        } else {
            assertEquals(ThreadPolicy.NON_REALTIME, grant.granted(), grant.toLine());
            assertEquals(0, proc.policy());
            assertEquals(1, grant.refusals().size(), grant.toLine());
            assertEquals(1, platform.warnings().warningsLogged());
        }
    }

    @Test
    void shouldRefuseWithEinvalAndWarnOnceWhenPriorityIsOutOfRange() throws Exception {
        var platform = new Platform(new RefusalWarnings());
        List<ThreadGrant> grants = List.of(
                onFreshThread(() -> platform.configureCurrentThread(ThreadPolicy.fifo(100), CpuSet.inherit())),
                onFreshThread(() -> platform.configureCurrentThread(ThreadPolicy.fifo(0), CpuSet.inherit())),
                onFreshThread(() -> platform.configureCurrentThread(ThreadPolicy.roundRobin(100), CpuSet.inherit())));
        for (ThreadGrant grant : grants) {
            assertEquals(ThreadPolicy.NON_REALTIME, grant.granted(), grant.toLine());
            assertFalse(grant.isPolicyGranted());
            PlatformRefusal refusal = grant.refusals().getFirst();
            assertEquals("thread priority", refusal.feature());
            if (platform.isAvailable()) {
                assertEquals("EINVAL", refusal.errnoName(), refusal.toString());
                assertEquals(22, refusal.errno());
                assertTrue(refusal.fix().contains("[1, 99]"), refusal.fix());
            } else {
                assertEquals("ENOSYS", refusal.errnoName(), refusal.toString());
            }
            assertTrue(grant.toLine().contains("granted SCHED_OTHER"), grant.toLine());
        }
        assertEquals(1, platform.warnings().warningsLogged(), "one warning for three refusals of one kind");
    }

    @Test
    void shouldLeaveTheWarningToTheCallerWhenConfiguringWithoutWarning() throws Exception {
        var platform = new Platform(new RefusalWarnings());
        ThreadGrant grant = onFreshThread(
                () -> platform.configureCurrentThreadWithoutWarning(ThreadPolicy.fifo(100), CpuSet.inherit()));

        assertEquals(1, grant.refusals().size(), grant.toLine());
        assertEquals(0, platform.warnings().warningsLogged());
        platform.warnOnce(grant.refusals());
        platform.warnOnce(grant.refusals());
        assertEquals(1, platform.warnings().warningsLogged());
    }

    @Test
    void shouldReturnToSchedOtherWhenAskedForNonRealtime() throws Exception {
        var platform = new Platform(new RefusalWarnings());
        ThreadGrant grant = onFreshThread(() -> {
            platform.configureCurrentThread(ThreadPolicy.fifo(5), CpuSet.inherit());
            return platform.configureCurrentThread(ThreadPolicy.NON_REALTIME, CpuSet.inherit());
        });
        assertEquals(ThreadPolicy.NON_REALTIME, grant.granted());
        assertTrue(grant.refusals().isEmpty(), grant.toLine());
    }

    @Test
    void shouldPinTheThreadWhenGivenOneCpuAndRefuseWhenTheCpuDoesNotExist() throws Exception {
        var platform = new Platform(new RefusalWarnings());
        ThreadGrant pinned = onFreshThread(() -> platform.configureCurrentThread(ThreadPolicy.NON_REALTIME,
                CpuSet.of(0)));
        ThreadGrant impossible = onFreshThread(() -> platform.configureCurrentThread(ThreadPolicy.NON_REALTIME,
                CpuSet.of(1000)));
        if (platform.isAvailable()) {
            assertArrayEquals(new int[] {0}, pinned.grantedCpus().cpus(), pinned.toLine());
            assertTrue(pinned.refusals().isEmpty(), pinned.toLine());
            assertEquals("EINVAL", impossible.refusals().getFirst().errnoName(), impossible.toLine());
            assertTrue(impossible.refusals().getFirst().fix().contains("allowed: "), impossible.toLine());
            assertFalse(impossible.grantedCpus().contains(1000));
        } else {
            assertEquals("ENOSYS", pinned.refusals().getFirst().errnoName());
        }
    }

    @Test
    void shouldStartThreadsSpawnedByARealtimeThreadAtSchedOtherWhenGranted() throws Exception {
        var platform = new Platform(new RefusalWarnings());
        Object[] policies = onFreshThread(() -> {
            ThreadPolicy parent = platform.configureCurrentThread(ThreadPolicy.fifo(10), CpuSet.inherit()).granted();
            ThreadPolicy[] child = new ThreadPolicy[1];
            Thread spawned = Thread.ofPlatform().start(() -> child[0] = platform.currentThreadPolicy());
            try {
                spawned.join();
            } catch (InterruptedException e) {
                throw new IllegalStateException(e);
            }
            return new Object[] {parent, child[0]};
        });
        assertEquals(ThreadPolicy.NON_REALTIME, policies[1],
                "SCHED_RESET_ON_FORK: a thread a dispatcher creates does not inherit its real-time priority");
        if (platform.isAvailable() && OsThreadStat.hasCapSysNice()) {
            assertEquals(ThreadPolicy.fifo(10), policies[0]);
        }
    }

    @Test
    void shouldReadTheRealtimePriorityLimitWhenOnLinux() {
        var platform = Platform.current();
        assertEquals(platform.isAvailable(), platform.realtimePriorityLimit().isPresent());
        assertEquals(platform.isAvailable(), platform.currentThreadId() > 0);
    }

    /** Runs {@code action} on a new platform thread and returns its result; its failure fails the caller. */
    static <T> T onFreshThread(Supplier<T> action) throws InterruptedException {
        var result = new AtomicReference<T>();
        var failure = new AtomicReference<Throwable>();
        Thread thread = Thread.ofPlatform().start(() -> {
            try {
                result.set(action.get());
            } catch (Throwable t) {
                failure.set(t);
            }
        });
        thread.join();
        if (failure.get() != null) {
            throw new AssertionError("action failed on its thread", failure.get());
        }
        return result.get();
    }

    @Test
    void shouldKeepOrdinaryThreadsOffTheRealtimeCpusOfAPartitionUntilItCloses() throws Exception {
        Split split = lastCpuRealtimeOrSkip();
        int[] allowed = split.allowed();
        CpuSet realtime = split.realtime();
        CpuSet ordinary = split.ordinary();
        var platform = Platform.current();
        assertThrows(IllegalArgumentException.class, () -> platform.partitionCpus(CpuSet.of(allowed)),
                "a partition must leave a CPU for the other threads");
        assertThrows(IllegalArgumentException.class, () -> platform.partitionCpus(CpuSet.of(CpuSet.MAX_CPUS - 1)),
                "a CPU that is not online");
        try (CpuPartition partition = platform.partitionCpus(realtime)) {
            assertEquals(ordinary, partition.ordinaryCpus());
            assertArrayEquals(ordinary.cpus(), io.etherware.rt.platform.internal.LinuxNative.getAffinity(0),
                    "the caller, an ordinary thread, was moved off the real-time CPU");
            assertThrows(IllegalStateException.class, () -> platform.partitionCpus(ordinary),
                    "one partition per JVM");
            CpuPartition second = platform.partitionCpus(realtime);
            second.close();
            second.close(); // a holder's second close does nothing
            assertEquals(realtime, platform.cpuPartition().orElseThrow().realtimeCpus(),
                    "still held by the first holder");
            // Placed by the platform: a real-time request on inherited CPUs, and an explicit one.
            ThreadGrant realtimeGrant = onFreshThread(
                    () -> platform.configureCurrentThreadWithoutWarning(ThreadPolicy.fifo(1), CpuSet.inherit()));
            assertEquals(realtime, realtimeGrant.grantedCpus(), realtimeGrant.toLine());
            // An ordinary thread that lands on the real-time CPU by inheritance (as one started by
            // a pinned real-time thread does) is moved back by the keeper; one the platform placed
            // there on request stays.
            int[][] seen = onFreshThread(() -> {
                ThreadGrant placed = platform.configureCurrentThreadWithoutWarning(ThreadPolicy.NON_REALTIME, realtime);
                int[][] affinities = new int[2][];
                Thread inheriting = Thread.ofPlatform().start(() -> affinities[1] = awaitAffinityChange(realtime));
                try {
                    inheriting.join();
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                }
                // The sweep that moved the inheriting thread looked at this one too.
                affinities[0] = io.etherware.rt.platform.internal.LinuxNative.getAffinity(0);
                assertEquals(realtime, placed.grantedCpus());
                return affinities;
            });
            assertArrayEquals(realtime.cpus(), seen[0], "placed on request: left alone");
            assertArrayEquals(ordinary.cpus(), seen[1], "inherited: moved back to the ordinary CPUs");
            assertTrue(partition.threadsMovedBack() >= 1, partition.describe());
        }
        assertTrue(platform.cpuPartition().isEmpty());
        assertArrayEquals(allowed, io.etherware.rt.platform.internal.LinuxNative.getAffinity(0),
                "closed: the moved threads may use their CPUs again");
    }

    @Test
    void shouldReadTheSameThreadIdFromProcAsFromGettid() throws Exception {
        org.junit.jupiter.api.Assumptions.assumeTrue(io.etherware.rt.platform.internal.LinuxNative.isAvailable(),
                "Linux only");
        // The fallback where libc has no gettid (glibc before 2.30) reads this link.
        var link = java.nio.file.Files.readSymbolicLink(java.nio.file.Path.of("/proc/thread-self"));
        assertEquals(Platform.current().currentThreadId(), Integer.parseInt(link.getFileName().toString()));
    }

    @Test
    void shouldPartitionFromAThreadThatMayNotRunOnTheRealtimeCpus() throws Exception {
        Split split = lastCpuRealtimeOrSkip();
        int[] allowed = split.allowed();
        CpuSet realtime = split.realtime();
        CpuSet ordinary = split.ordinary();
        // A JVM started by a partitioned one inherits only the ordinary CPUs, and partitions too.
        CpuSet granted = onFreshThread(() -> {
            io.etherware.rt.platform.internal.LinuxNative.setAffinity(0, ordinary.cpus());
            try (CpuPartition partition = Platform.current().partitionCpus(realtime)) {
                assertEquals(ordinary, partition.ordinaryCpus());
                return Platform.current().configureCurrentThreadWithoutWarning(ThreadPolicy.NON_REALTIME, realtime)
                        .grantedCpus();
            }
        });
        assertEquals(realtime, granted, "the real-time CPU is usable though the opener could not run there");
        assertArrayEquals(allowed, io.etherware.rt.platform.internal.LinuxNative.getAffinity(0),
                "closed: this thread, moved by the partition, is back on its CPUs");
    }

    /** This thread's CPUs, split into the last one (real-time) and the rest (ordinary). */
    private record Split(int[] allowed, CpuSet realtime, CpuSet ordinary) {
    }

    /** The split of this thread's CPUs; skips the test off Linux or with fewer than two CPUs. */
    private static Split lastCpuRealtimeOrSkip() {
        org.junit.jupiter.api.Assumptions.assumeTrue(io.etherware.rt.platform.internal.LinuxNative.isAvailable(),
                "Linux only");
        int[] allowed = io.etherware.rt.platform.internal.LinuxNative.getAffinity(0);
        org.junit.jupiter.api.Assumptions.assumeTrue(allowed.length >= 2, "needs two CPUs");
        return new Split(allowed, CpuSet.of(allowed[allowed.length - 1]),
                CpuSet.of(java.util.Arrays.copyOf(allowed, allowed.length - 1)));
    }

    /** This thread's CPUs once they differ from {@code from}, or after five keeper periods. */
    private static int[] awaitAffinityChange(CpuSet from) {
        long untilNs = System.nanoTime() + 5 * CpuPartition.KEEPER_PERIOD_NS;
        int[] affinity = io.etherware.rt.platform.internal.LinuxNative.getAffinity(0);
        while (java.util.Arrays.equals(affinity, from.cpus()) && System.nanoTime() < untilNs) {
            java.util.concurrent.locks.LockSupport.parkNanos(10_000_000);
            affinity = io.etherware.rt.platform.internal.LinuxNative.getAffinity(0);
        }
        return affinity;
    }
}
