package io.etherware.examples.scenario;

import io.etherware.pendulum.components.ControlCycle;
import io.etherware.pendulum.components.ControlListener;
import io.etherware.pendulum.components.ControlRecorder;
import java.util.List;
import java.util.concurrent.atomic.AtomicLong;

/**
 * The controller's cycles of one run: kept for the CSV and the summary (a
 * {@link ControlRecorder}), and counted as they come for the progress line.
 *
 * <p>{@link #onCycle} is called on the controller's dispatcher: it appends and increments, never
 * blocks. The readers may be called from any thread.
 */
public final class CycleLog implements ControlListener {

    private final ControlRecorder recorder;
    private final long periodNs;
    private final AtomicLong onTime = new AtomicLong();

    /** A log of up to {@code capacity} cycles of a loop with period {@code periodNs}. */
    public CycleLog(int capacity, long periodNs) {
        this.recorder = new ControlRecorder(capacity);
        this.periodNs = periodNs;
    }

    @Override
    public void onCycle(ControlCycle cycle) {
        recorder.onCycle(cycle);
        if (isOnTime(cycle, periodNs)) {
            onTime.incrementAndGet();
        }
    }

    /** Whether the cycle sent its torque command within its own period. */
    public static boolean isOnTime(ControlCycle cycle, long periodNs) {
        return cycle.outcome() == ControlCycle.Outcome.COMMANDED && cycle.responseNs() <= periodNs;
    }

    /** Cycles that sent their torque within the period, so far. */
    public long onTimeCycles() {
        return onTime.get();
    }

    /** The cycles recorded, in order. */
    public List<ControlCycle> cycles() {
        return recorder.cycles();
    }

    /** Cycles not kept because the log was full. */
    public long dropped() {
        return recorder.dropped();
    }
}
