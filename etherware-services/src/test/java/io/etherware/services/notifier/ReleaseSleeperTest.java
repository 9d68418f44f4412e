package io.etherware.services.notifier;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.etherware.services.notifier.internal.ReleaseSleeper;
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
        var spinning = new ReleaseSleeper(clock, 0, deadlineNs -> {
            kernelSleeps.add(deadlineNs);
            clock.set(deadlineNs + 50_000); // woke past the release: no spin left
        });
        spinning.sleepUntil(clock.nanoTime() + 100_000);
        assertEquals(1, kernelSleeps.size());
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
        sleeper.sleepUntil(clock.nanoTime() - 1); // past: returns at once
        sleeper.sleepUntil(clock.nanoTime() + 100_000); // parks 0.1 ms of real time, returns early
        assertEquals(List.of(), kernelSleeps);
    }
}
