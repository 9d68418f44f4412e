package io.etherware.rt.platform.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.ThreadPolicy;
import org.junit.jupiter.api.Test;

class RefusalAdviceTest {

    @Test
    void shouldNameCapabilityAndLimitWhenSchedFifoIsNotPermitted() {
        String fix = RefusalAdvice.forPolicy(ThreadPolicy.fifo(80), Errno.EPERM, new long[] {0, 0}, 1, 99);
        assertTrue(fix.contains("setcap cap_sys_nice+ep"), fix);
        assertTrue(fix.contains("RLIMIT_RTPRIO (now soft=0, hard=0) to at least 80"), fix);
        assertTrue(fix.contains("/etc/security/limits.conf"), fix);
    }

    @Test
    void shouldPointAtContainerOrCgroupWhenTheLimitAllowsItButTheOsStillRefuses() {
        String fix = RefusalAdvice.forPolicy(ThreadPolicy.fifo(80), Errno.EPERM,
                new long[] {LinuxNative.RLIM_INFINITY, LinuxNative.RLIM_INFINITY}, 1, 99);
        assertTrue(fix.startsWith("RLIMIT_RTPRIO (soft=unlimited, hard=unlimited) allows it"), fix);
        assertTrue(fix.contains("cpu.rt_runtime_us"), fix);
    }

    @Test
    void shouldGiveTheRangeWhenThePriorityIsInvalid() {
        assertEquals("priority 100 is outside SCHED_RR's range [1, 99] on this kernel; configure a priority inside it",
                RefusalAdvice.forPolicy(ThreadPolicy.roundRobin(100), Errno.EINVAL, null, 1, 99));
    }

    @Test
    void shouldListAllowedCpusWhenAffinityIsImpossible() {
        String fix = RefusalAdvice.forAffinity(CpuSet.of(7), Errno.EINVAL, new int[] {0, 1, 2});
        assertTrue(fix.contains("allowed: 0-2"), fix);
    }

    @Test
    void shouldNameMemlockWhenMlockallIsRefused() {
        assertTrue(RefusalAdvice.forMemoryLock(Errno.ENOMEM).contains("RLIMIT_MEMLOCK"));
        assertEquals("EPERM (errno 1: Operation not permitted)", Errno.describe(Errno.EPERM));
        assertEquals("errno 200", Errno.name(200));
    }
}
