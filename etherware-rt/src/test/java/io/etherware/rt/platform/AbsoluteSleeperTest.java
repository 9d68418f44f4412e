package io.etherware.rt.platform;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeTrue;

import io.etherware.core.time.DeadlineSleeper;
import io.etherware.core.time.NodeClock;
import java.nio.file.Files;
import java.nio.file.Path;
import org.junit.jupiter.api.Test;

class AbsoluteSleeperTest {

    @Test
    void shouldSleepInTheKernelUntilTheDeadlineAndNotBeforeWhenAvailable() {
        assumeTrue(Platform.current().isAvailable(), "Linux only");
        assertTrue(AbsoluteSleeper.isAvailable(), AbsoluteSleeper.unavailableReason().orElse(""));
        DeadlineSleeper sleeper = AbsoluteSleeper.forClock(NodeClock.system());
        assertEquals("clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME)", AbsoluteSleeper.describe(sleeper));
        for (int i = 0; i < 20; i++) {
            long deadlineNs = System.nanoTime() + 2_000_000L;
            sleeper.sleepUntil(deadlineNs);
            long nowNs = System.nanoTime();
            assertTrue(nowNs >= deadlineNs, "woke " + (deadlineNs - nowNs) + " ns before the deadline");
        }
        long beforeNs = System.nanoTime();
        sleeper.sleepUntil(beforeNs - 1_000_000_000L);
        sleeper.sleepUntil(Long.MIN_VALUE);
        assertTrue(System.nanoTime() - beforeNs < 1_000_000_000L, "a past deadline returns at once");
    }

    @Test
    void shouldParkOnAClockThatIsNotTheSystemClock() {
        var manual = new NodeClock() {
            @Override
            public long nanoTime() {
                return 0;
            }

            @Override
            public long epochNanos() {
                return 0;
            }
        };
        DeadlineSleeper sleeper = AbsoluteSleeper.forClock(manual);
        assertFalse(sleeper instanceof AbsoluteSleeper, "the kernel knows only the system clock");
        assertTrue(AbsoluteSleeper.describe(sleeper).startsWith("LockSupport.parkNanos"));
        sleeper.sleepUntil(-1); // past on that clock: returns at once
    }

    @Test
    void shouldHoldTheCpuLatencyWhenPermittedElseSayWhyAndReleaseOnClose() {
        boolean exists = Files.exists(Path.of(CpuLatencyHold.DEVICE));
        boolean writable = Files.isWritable(Path.of(CpuLatencyHold.DEVICE));
        try (CpuLatencyHold hold = CpuLatencyHold.request()) {
            assertEquals(writable, hold.isHeld(), hold.state());
            assertEquals(exists && !writable, hold.refusal().isPresent(), "a missing device is not a refusal: "
                    + hold.state());
            assertTrue(hold.state().startsWith("cpu latency: "), hold.state());
            hold.close(); // idempotent with the close of the try
        }
        CpuLatencyHold none = CpuLatencyHold.none();
        assertFalse(none.isHeld());
        assertTrue(none.refusal().isEmpty());
    }
}
