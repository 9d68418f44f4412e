package io.etherware.examples.stress;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.message.Tick;
import io.etherware.core.time.NodeClock;
import io.etherware.examples.scenario.ScenarioEvent;
import io.etherware.examples.scenario.ScenarioEvents;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import org.junit.jupiter.api.Test;

class StressComponentTest {

    /** A clock that advances 1 µs per reading. */
    private static final class SteppingClock implements NodeClock {
        final AtomicLong nowNs = new AtomicLong();

        @Override
        public long nanoTime() {
            return nowNs.addAndGet(1_000L);
        }

        @Override
        public long epochNanos() {
            return nowNs.get();
        }
    }

    @Test
    void shouldComputeUntilItsDeadlineOnTheClock() {
        var clock = new SteppingClock();
        StressComponent.compute(clock, 50_000L, Long.MAX_VALUE);
        assertEquals(50_000L, clock.nowNs.get(), "one clock reading per chunk, stopping at the deadline");
    }

    @Test
    void shouldStopAtTheChunkCapEvenIfTheClockNeverMoves() {
        NodeClock frozen = new NodeClock() {
            @Override
            public long nanoTime() {
                return 0L;
            }

            @Override
            public long epochNanos() {
                return 0L;
            }
        };
        long startNs = System.nanoTime();
        StressComponent.compute(frozen, 1L, 3);
        assertTrue(System.nanoTime() - startNs < TimeUnit.SECONDS.toNanos(5), "bounded by the cap");
    }

    @Test
    void shouldMarkEachActivationAndHoldItsDispatcherForItsWork() throws Exception {
        var events = new ScenarioEvents();
        long workNs = TimeUnit.MILLISECONDS.toNanos(30);
        try (var node = EtherwareNode.builder().nodeId("stress-test").build()) {
            node.add(StressComponent.PROFILE, () -> new StressComponent(workNs, events));
            node.start();
            node.send(StressComponent.PROFILE, new Text("not a tick"), QoS.NONE);
            node.send(StressComponent.PROFILE, new Tick(System.nanoTime(), 0, 5_000_000_000L),
                    QoS.periodic(Criticality.LOW, 5_000_000_000L));
            long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(10);
            while (events.snapshot().size() < 2 && System.nanoTime() < deadlineNs) {
                Thread.sleep(5);
            }
        }
        List<ScenarioEvent> marks = events.snapshot();
        assertEquals(List.of("stress 1 start", "stress 1 end"), marks.stream().map(ScenarioEvent::label).toList());
        assertTrue(marks.get(1).timeNs() - marks.get(0).timeNs() >= workNs, "computed for its whole work");
    }
}
