package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Profile;
import io.etherware.core.scheduler.Job;
import io.etherware.core.testing.ManualScheduler;
import io.etherware.core.testing.Num;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/**
 * The race the reservation exists for, staged step by step with a hand-driven scheduler: a
 * component frees up while a dispatcher holds a just-taken job for it, and an earlier job of the
 * same source waits parked.
 */
class ReservationTest {

    private static final Profile TARGET = Profile.of("target");

    @Test
    void shouldRunTheParkedJobBeforeTheJustTakenOneWhenTheComponentFreesInBetween() throws Exception {
        // Values >= 100 come "from the other source" and go to dispatcher 1; the rest to 0.
        var scheduler = new ManualScheduler(2, job -> job.message().contentsAs(Num.class).value() >= 100 ? 1 : 0);
        var handled = new CopyOnWriteArrayList<Long>();
        var entered = new CountDownLatch(1);
        var unblock = new CountDownLatch(1);
        try (var node = EtherwareNode.builder().nodeId("race").scheduler(() -> scheduler)
                .drainTimeout(Duration.ZERO).build()) {
            node.add(TARGET, () -> (message, context) -> {
                long value = message.contentsAs(Num.class).value();
                if (value == 100) {
                    entered.countDown();
                    assertTrue(unblock.await(10, TimeUnit.SECONDS));
                }
                handled.add(value);
            });
            node.start();
            node.send(TARGET, new Num(100));
            node.send(TARGET, new Num(1));
            node.send(TARGET, new Num(2));

            // Dispatcher 1 enters the component and stays inside.
            Future<Boolean> busy = scheduler.runAsync(1, scheduler.take(1));
            assertTrue(entered.await(10, TimeUnit.SECONDS));

            // Dispatcher 0 takes job 1: the component is busy, so it is parked.
            Job first = scheduler.take(0);
            assertFalse(scheduler.run(0, first), "job 1 must wait for the busy component");
            assertFalse(first.isReserved());

            // Dispatcher 0 takes job 2 but has not run it yet; meanwhile the component frees up.
            Job second = scheduler.take(0);
            unblock.countDown();
            assertTrue(busy.get(10, TimeUnit.SECONDS));

            // The kernel handed job 1 back, reserved, on its own dispatcher.
            assertEquals(1, scheduler.queued(0));
            // Job 2 must not overtake it: the component is reserved for job 1.
            assertFalse(scheduler.run(0, second), "job 2 must not overtake the reserved job 1");

            Job handedBack = scheduler.take(0);
            assertEquals(first, handedBack);
            assertTrue(handedBack.isReserved());
            assertEquals(0, handedBack.dispatcherId(), "placement is kept");
            assertTrue(scheduler.run(0, handedBack), "a reserved job always runs when taken");

            Job secondBack = scheduler.take(0);
            assertEquals(second, secondBack);
            assertTrue(scheduler.run(0, secondBack));

            assertEquals(List.of(100L, 1L, 2L), handled);
        }
    }

    @Test
    void shouldGiveTheMostUrgentWaitingJobTheComponentWhenSeveralWait() throws Exception {
        // Dispatcher = value modulo 3; urgency is arrival order (the default).
        var scheduler = new ManualScheduler(3, job -> (int) (job.message().contentsAs(Num.class).value() % 3));
        var handled = new CopyOnWriteArrayList<Long>();
        var entered = new CountDownLatch(1);
        var unblock = new CountDownLatch(1);
        try (var node = EtherwareNode.builder().nodeId("urgency").scheduler(() -> scheduler)
                .drainTimeout(Duration.ZERO).build()) {
            node.add(TARGET, () -> (message, context) -> {
                long value = message.contentsAs(Num.class).value();
                if (value == 0) {
                    entered.countDown();
                    assertTrue(unblock.await(10, TimeUnit.SECONDS));
                }
                handled.add(value);
            });
            node.start();
            node.send(TARGET, new Num(0)); // dispatcher 0, blocks inside
            node.send(TARGET, new Num(1)); // dispatcher 1
            node.send(TARGET, new Num(2)); // dispatcher 2
            Future<Boolean> busy = scheduler.runAsync(0, scheduler.take(0));
            assertTrue(entered.await(10, TimeUnit.SECONDS));
            Job two = scheduler.take(2);
            Job one = scheduler.take(1);
            assertFalse(scheduler.run(2, two)); // parked first, but it arrived later
            assertFalse(scheduler.run(1, one));
            unblock.countDown();
            assertTrue(busy.get(10, TimeUnit.SECONDS));
            // Job 1 arrived first, so it is more urgent and gets the component first.
            assertEquals(1, scheduler.queued(1));
            assertEquals(0, scheduler.queued(2));
            assertTrue(scheduler.run(1, scheduler.take(1)));
            assertTrue(scheduler.run(2, scheduler.take(2)));
            assertEquals(List.of(0L, 1L, 2L), handled);
        }
    }
}
