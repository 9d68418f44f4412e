package io.etherware.services.notifier;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.services.notifier.internal.ReleaseSleeper;
import io.etherware.testkit.ManualClock;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

class ReleaseSleeperTest {

    private final ManualClock clock = new ManualClock(1_000_000_000L);
    private final List<Long> kernelSleeps = new ArrayList<>();

    @Test
    void shouldSleepTheLastStretchInTheKernelToTheReleaseTimeMinusTheSpin() {
        var sleeper = new ReleaseSleeper(clock, 0, kernelSleeps::add);
        long releaseNs = clock.nanoTime() + ReleaseSleeper.KERNEL_WINDOW_NS / 2;
        sleeper.sleepUntil(releaseNs);
        assertEquals(List.of(releaseNs), kernelSleeps, "within the window: straight to the kernel");

        kernelSleeps.clear();
        long spinNs = 20_000;
        var spinning = new ReleaseSleeper(clock, spinNs, deadlineNs -> {
            kernelSleeps.add(deadlineNs);
            clock.set(deadlineNs + spinNs); // woke at the release: no spin left
        });
        long nextReleaseNs = clock.nanoTime() + 100_000;
        spinning.sleepUntil(nextReleaseNs);
        assertEquals(List.of(nextReleaseNs - spinNs), kernelSleeps, "the kernel sleep ends where the spin begins");
    }

    @Test
    void shouldParkAndReturnEarlyWithoutTheKernelWhileTheReleaseIsBeyondTheWindow() {
        var sleeper = new ReleaseSleeper(clock, 0, kernelSleeps::add);
        // The manual clock does not move: the park (1 ms of real time) ends with the release still
        // beyond the window, so the caller must look again; an unpark would end it the same way.
        sleeper.sleepUntil(clock.nanoTime() + ReleaseSleeper.KERNEL_WINDOW_NS + 1_000_000L);
        assertEquals(List.of(), kernelSleeps, "parked, so an unpark (a new subscription, a close) can end the wait");
    }

    @Test
    void shouldOnlyParkWithoutAKernelSleeper() {
        var sleeper = new ReleaseSleeper(clock, 0, null);
        java.util.concurrent.locks.LockSupport.parkNanos(1); // takes a stale permit, if any
        long startNs = System.nanoTime();
        sleeper.sleepUntil(clock.nanoTime() - 1); // past: returns at once
        sleeper.sleepUntil(clock.nanoTime() + 2_000_000L); // parks 2 ms of real time, then returns early
        long sleptNs = System.nanoTime() - startNs;
        assertTrue(sleptNs >= 1_000_000L, "parked for the time left on its clock, not returned at once: " + sleptNs);
        assertEquals(1_000_000_000L, clock.nanoTime(), "its clock did not move; the caller looks again");
    }
}
