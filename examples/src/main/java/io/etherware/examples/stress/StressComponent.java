package io.etherware.examples.stress;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Tick;
import io.etherware.core.time.NodeClock;
import io.etherware.examples.scenario.ScenarioEvent;
import io.etherware.examples.scenario.ScenarioEvents;
import java.util.Objects;

/**
 * The paper's stressing task (Section VI-B, Fig. 7, component S): on each LOW Tick it computes
 * for a fixed stretch of time, about a second, holding the dispatcher that runs it. It marks the
 * start and end of each activation as scenario events.
 *
 * <p>The work is bounded twice: by the node's clock ({@code workNs} after it starts) and by an
 * iteration cap, so it ends even if the clock misbehaves. Called by the kernel one message at a
 * time; it blocks its dispatcher for {@code workNs} by design — that is the stress.
 */
public final class StressComponent implements Component {

    /** The stressing task's profile, {@code stress[pendulum=1]}. */
    public static final Profile PROFILE = Profile.of("stress", "pendulum", "1");

    /** Iterations of the inner loop between clock reads: tens of microseconds of work. */
    private static final int CHUNK = 10_000;

    private final long workNs;
    private final ScenarioEvents events;
    private long activations;
    private volatile double sink;

    /** A stressing task computing {@code workNs} per activation. */
    public StressComponent(long workNs, ScenarioEvents events) {
        if (workNs <= 0) {
            throw new IllegalArgumentException("workNs=" + workNs + ": must be > 0");
        }
        this.workNs = workNs;
        this.events = Objects.requireNonNull(events, "events");
    }

    @Override
    public void onMessage(Message message, ComponentContext context) {
        if (!(message.contents() instanceof Tick)) {
            return;
        }
        activations++;
        NodeClock clock = context.clock();
        long startNs = clock.nanoTime();
        events.add(startNs, ScenarioEvent.Kind.STRESS_START, "stress " + activations + " start");
        sink = compute(clock, startNs + workNs, Math.max(1, workNs / 1_000));
        events.add(clock.nanoTime(), ScenarioEvent.Kind.STRESS_END, "stress " + activations + " end");
    }

    /**
     * Arithmetic until {@code untilNs} on {@code clock} or {@code maxChunks} chunks of work,
     * whichever comes first; returns a value so the JIT cannot drop the work.
     */
    static double compute(NodeClock clock, long untilNs, long maxChunks) {
        double x = 0.5;
        for (long chunk = 0; chunk < maxChunks && clock.nanoTime() - untilNs < 0; chunk++) {
            for (int i = 1; i <= CHUNK; i++) {
                x = x * 3.9 * (1.0 - x) + 1e-9 * Math.sqrt(i); // the logistic map: cheap, never constant
                x -= Math.floor(x);
            }
        }
        return x;
    }

    @Override
    public String toString() {
        return "StressComponent[workNs=" + workNs + ", activations=" + activations + ", sink=" + (sink > 0) + "]";
    }
}
