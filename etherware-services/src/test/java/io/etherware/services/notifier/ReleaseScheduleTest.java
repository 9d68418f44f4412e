package io.etherware.services.notifier;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Tick;
import io.etherware.services.notifier.internal.ReleaseSchedule;
import io.etherware.services.notifier.internal.SubscriptionState;
import io.etherware.testkit.ManualClock;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The release rule step by step, on the test thread: back-pressure from a stalled receiver,
 * unresolved targets, retargeting and cancelling. Deterministic, no threads.
 */
class ReleaseScheduleTest {

    private static final long T0_NS = 1_000_000_000L;
    private static final long PERIOD_NS = 10_000_000L;
    private static final Profile NOTIFIER = Notifier.profileFor("test");
    private static final Profile RECEIVER = Profile.of("controller");
    private static final Profile STANDBY = Profile.of("controller", "site", "b");

    private final ManualClock clock = new ManualClock(T0_NS);
    private final RecordingKernel kernel = new RecordingKernel(clock);
    private final ReleaseSchedule schedule = new ReleaseSchedule(kernel, clock, NOTIFIER);
    private final List<SubscriptionState> finished = new ArrayList<>();
    private long order;

    @Test
    void shouldSkipAndCountReleasesWhileTheReceiverHasNotFinishedThePreviousTick() {
        RecordingKernel.FakeShell receiver = kernel.addReceiver(RECEIVER, false);
        SubscriptionState state = add(periodic("loop", RECEIVER));

        fireAt(0);   // #0 goes out
        fireAt(1);   // the receiver is stuck on #0: skipped
        fireAt(2);   // still stuck: skipped
        receiver.finishOne();
        fireAt(3);   // #0 done: #3 goes out
        fireAt(4);   // stuck on #3
        receiver.finishOne();
        fireAt(5);

        assertEquals(List.of(0L, 3L, 5L), sentSequences());
        SubscriptionStats stats = state.stats();
        assertEquals(3, stats.skippedBusy());
        assertEquals(3, stats.ticksSent());
        assertEquals(0, stats.skippedLate());
        assertEquals(3, stats.skippedReleases());
    }

    @Test
    void shouldQueueAtMostOneTickBehindAReceiverThatStallsOnOtherWork() {
        RecordingKernel.FakeShell receiver = kernel.addReceiver(RECEIVER, false);
        add(periodic("loop", RECEIVER));
        fireAt(0);
        receiver.finishOne(); // #0 handled; the receiver then stalls on some other message
        for (int k = 1; k <= 50; k++) {
            fireAt(k);
        }
        assertEquals(List.of(0L, 1L), sentSequences(), "one Tick waits behind the stall, not fifty");
    }

    @Test
    void shouldSendEveryReleaseWhenBackPressureIsOffOrTheReceiverIsRemote() {
        kernel.addReceiver(RECEIVER, false);
        Profile remote = Profile.of("controller", "node", "far");
        kernel.addRemote(remote);
        add(periodic("local", RECEIVER).withBackPressure(false));
        add(periodic("remote", remote));
        for (int k = 0; k < 5; k++) {
            fireAt(k);
        }
        assertEquals(5, kernel.sent().stream().filter(message -> message.profile().equals(RECEIVER)).count());
        assertEquals(5, kernel.sent().stream().filter(message -> message.profile().equals(remote)).count());
    }

    @Test
    void shouldSkipAndCountReleasesWhoseTargetDoesNotResolveAndResumeWhenItDoes() {
        SubscriptionState state = add(periodic("loop", RECEIVER));
        fireAt(0);
        fireAt(1);
        kernel.addReceiver(RECEIVER, true);
        fireAt(2);
        kernel.removeReceiver(RECEIVER);
        fireAt(3);

        assertEquals(List.of(2L), sentSequences());
        assertEquals(3, state.stats().skippedUndeliverable());
        assertEquals(1, state.stats().ticksSent());
    }

    @Test
    void shouldCountTicksTheKernelRefusesAndKeepReleasing() {
        kernel.addReceiver(RECEIVER, true);
        SubscriptionState state = add(periodic("loop", RECEIVER));
        kernel.refuseSends(true);
        fireAt(0);
        fireAt(1);
        kernel.refuseSends(false);
        fireAt(2);

        assertEquals(List.of(2L), sentSequences());
        assertEquals(2, state.stats().skippedUndeliverable());
        assertEquals(3, state.stats().nextSequence());
    }

    @Test
    void shouldSendToTheNewTargetFromTheNextReleaseOnKeepingTheSequence() {
        kernel.addReceiver(RECEIVER, true);
        kernel.addReceiver(STANDBY, true);
        SubscriptionState state = add(periodic("loop", RECEIVER));
        fireAt(0);
        fireAt(1);
        state.retarget(STANDBY);
        fireAt(2);
        fireAt(3);

        List<Message> sent = kernel.sent();
        assertEquals(List.of(RECEIVER, RECEIVER, STANDBY, STANDBY), sent.stream().map(Message::profile).toList());
        assertEquals(List.of(0L, 1L, 2L, 3L), sentSequences());
        assertEquals(STANDBY, state.stats().subscription().target());
    }

    @Test
    void shouldReleaseNothingOnceCancelled() {
        kernel.addReceiver(RECEIVER, true);
        SubscriptionState state = add(periodic("loop", RECEIVER));
        fireAt(0);
        state.cancel();
        fireAt(1);
        fireAt(2);
        assertEquals(List.of(0L), sentSequences());
        assertEquals(0, schedule.size(), "dropped from the queue when it surfaced");
    }

    @Test
    void shouldReportTheNextReleaseAndNothingWhenEmpty() {
        kernel.addReceiver(RECEIVER, true);
        assertEquals(Long.MAX_VALUE, schedule.fireDue(finished::add));
        add(periodic("loop", RECEIVER));
        assertEquals(T0_NS + PERIOD_NS, schedule.fireDue(finished::add), "#0 went out at t0; #1 is next");
        assertEquals(1, kernel.sentCount());
        add(Subscription.oneShot("once", RECEIVER, Criticality.LOW, T0_NS + PERIOD_NS / 2));
        clock.set(T0_NS + PERIOD_NS / 2);
        assertEquals(T0_NS + PERIOD_NS, schedule.fireDue(finished::add));
        assertEquals(List.of("once"), finished.stream().map(SubscriptionState::name).toList());
    }

    @Test
    void shouldRefuseAStateWithoutAFirstRelease() {
        var unset = Subscription.periodic("loop", RECEIVER, Criticality.HIGH, PERIOD_NS);
        assertThrows(IllegalArgumentException.class, () -> new SubscriptionState(unset, 0, T0_NS));
    }

    private Subscription periodic(String name, Profile target) {
        return Subscription.periodic(name, target, Criticality.HIGH, PERIOD_NS).startingAt(T0_NS);
    }

    private SubscriptionState add(Subscription subscription) {
        var state = new SubscriptionState(subscription, order++, clock.nanoTime());
        schedule.add(state);
        return state;
    }

    /** Moves the clock a little past release #k and fires what is due. */
    private void fireAt(long k) {
        clock.set(T0_NS + k * PERIOD_NS + 1_000);
        long nextNs = schedule.fireDue(finished::add);
        assertTrue(nextNs > clock.nanoTime(), "nothing due is left behind");
    }

    private List<Long> sentSequences() {
        return kernel.ticks().stream().map(Tick::sequence).toList();
    }
}
