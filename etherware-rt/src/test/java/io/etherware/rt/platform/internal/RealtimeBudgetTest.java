package io.etherware.rt.platform.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.rt.platform.ThreadPolicy;
import java.util.List;
import java.util.Optional;
import org.junit.jupiter.api.Test;

class RealtimeBudgetTest {

    @Test
    void shouldReadCapSysNiceFromTheEffectiveSet() {
        assertEquals(Optional.of(true), RealtimeBudget.capSysNice(List.of("Name:\tjava", "CapInh:\t0000000000000000",
                "CapEff:\t000001ffffffffff")));
        assertEquals(Optional.of(false), RealtimeBudget.capSysNice(List.of("CapEff:\t0000000000000000")));
        assertEquals(Optional.of(true), RealtimeBudget.capSysNice(List.of("CapEff:\t0000000000800000")));
        assertEquals(Optional.empty(), RealtimeBudget.capSysNice(List.of("Name:\tjava")));
    }

    @Test
    void shouldFindTheCpuHierarchyOfCgroupV1AndNoneOnV2Only() {
        assertEquals(Optional.of("/node-2"), RealtimeBudget.cpuGroup(List.of("4:memory:/x", "2:cpuacct:/",
                "1:cpu:/node-2", "0::/")));
        assertEquals(Optional.of("/a/b"), RealtimeBudget.cpuGroup(List.of("3:cpu,cpuacct:/a/b")));
        assertEquals(Optional.empty(), RealtimeBudget.cpuGroup(List.of("0::/user.slice")));
        assertEquals(Optional.empty(), RealtimeBudget.cpuGroup(List.of("2:cpuacct:/")));
    }

    @Test
    void shouldNameTheCgroupInsteadOfRootWhenAPrivilegedThreadsGroupHasNoBudget() {
        String fix = RefusalAdvice.forPolicy(ThreadPolicy.fifo(80), Errno.EPERM, new long[] {0, 0}, 1, 99,
                new RealtimeBudget(Optional.of(true), Optional.of("/node-2")));
        assertTrue(fix.contains("cgroup '/node-2' has no real-time budget (cpu.rt_runtime_us=0)"), fix);
        assertFalse(fix.contains("run as root"), fix);
    }

    @Test
    void shouldNotTellAPrivilegedThreadToRunAsRoot() {
        String fix = RefusalAdvice.forPolicy(ThreadPolicy.fifo(80), Errno.EPERM, new long[] {0, 0}, 1, 99,
                new RealtimeBudget(Optional.of(true), Optional.empty()));
        assertTrue(fix.contains("holds CAP_SYS_NICE"), fix);
        assertFalse(fix.contains("run as root"), fix);
    }

    @Test
    void shouldKeepTheLimitAdviceForAnUnprivilegedThread() {
        String fix = RefusalAdvice.forPolicy(ThreadPolicy.fifo(80), Errno.EPERM, new long[] {0, 0}, 1, 99,
                new RealtimeBudget(Optional.of(false), Optional.empty()));
        assertTrue(fix.contains("RLIMIT_RTPRIO (now soft=0, hard=0) to at least 80"), fix);
    }

    @Test
    void shouldReadThisThreadWithoutFailing() {
        RealtimeBudget budget = RealtimeBudget.ofCurrentThread();
        // On Linux the status file is there; elsewhere the probe says it does not know.
        if (System.getProperty("os.name").startsWith("Linux")) {
            assertTrue(budget.capSysNice().isPresent(), budget::toString);
        }
    }
}
