package io.etherware.services.notifier;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Tick;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.testkit.Await;
import io.etherware.testkit.ManualClock;
import java.util.ArrayList;
import java.util.List;
import java.util.Random;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/**
 * The Notifier thread on a manual clock (virtual time): exact release grids, overruns skipped and
 * counted instead of burst, whatever the thread's wake-ups do. Deterministic.
 */
class NotifierReleaseTest {

    private static final long T0_NS = 5_000_000_000L;
    private static final long PERIOD_NS = TimeUnit.MILLISECONDS.toNanos(1);
    private static final Profile RECEIVER = Profile.of("controller", "car", "1");
    private static final NotifierConfig CONFIG = NotifierConfig.defaults().withThreadPolicy(ThreadPolicy.NON_REALTIME);

    @Test
    void shouldReleaseTenThousandTicksAtExactlyT0PlusKPeriodWhenRunForTenVirtualSeconds() {
        int count = 10_000;
        var clock = new ManualClock(T0_NS - PERIOD_NS);
        var kernel = new RecordingKernel(clock);
        kernel.addReceiver(RECEIVER, true);
        var sleeper = new VirtualSleeper(clock, T0_NS + (count - 1) * PERIOD_NS, deadline -> 0);
        try (var notifier = new Notifier(kernel, CONFIG, clock, sleeper)) {
            notifier.subscribe(Subscription.periodic("loop", RECEIVER, Criticality.HIGH, PERIOD_NS).startingAt(T0_NS));
            notifier.start();
            Await.until(() -> kernel.sentCount() + " Ticks sent", 30_000, () -> kernel.sentCount() >= count);

            List<Tick> ticks = kernel.ticks();
            assertEquals(count, ticks.size());
            for (int k = 0; k < count; k++) {
                assertEquals(new Tick(T0_NS + k * PERIOD_NS, k, PERIOD_NS), ticks.get(k), "Tick #" + k);
            }
            SubscriptionStats stats = notifier.stats("loop").orElseThrow();
            assertEquals(count, stats.ticksSent());
            assertEquals(0, stats.skippedReleases());
            assertEquals(count, stats.nextSequence());
            assertEquals(0, stats.latenessNs().maxNs(), "virtual wake-ups are exact");
        }
    }

    @Test
    void shouldKeepTheGridExactWhenEveryWakeUpIsLateByUpToAThirdOfThePeriod() {
        int count = 2_000;
        var random = new Random(42);
        var clock = new ManualClock(T0_NS - PERIOD_NS);
        var kernel = new RecordingKernel(clock);
        kernel.addReceiver(RECEIVER, true);
        var sleeper = new VirtualSleeper(clock, T0_NS + (count - 1) * PERIOD_NS,
                deadline -> random.nextLong(PERIOD_NS / 3));
        try (var notifier = new Notifier(kernel, CONFIG, clock, sleeper)) {
            notifier.subscribe(Subscription.periodic("loop", RECEIVER, Criticality.HIGH, PERIOD_NS).startingAt(T0_NS));
            notifier.start();
            Await.until(() -> kernel.sentCount() + " Ticks sent", 30_000, () -> kernel.sentCount() >= count);

            List<Tick> ticks = kernel.ticks();
            List<Long> sentAtNs = kernel.sentAtNs();
            for (int k = 0; k < count; k++) {
                assertEquals(T0_NS + k * PERIOD_NS, ticks.get(k).releaseNs(), "late wake-ups must not drift the grid");
                long latenessNs = sentAtNs.get(k) - ticks.get(k).releaseNs();
                assertTrue(latenessNs >= 0 && latenessNs < PERIOD_NS / 3, "lateness of #" + k + ": " + latenessNs);
            }
            SubscriptionStats stats = notifier.stats("loop").orElseThrow();
            assertEquals(0, stats.skippedReleases());
            assertTrue(stats.latenessNs().maxNs() > 0, "lateness is recorded");
        }
    }

    @Test
    void shouldSkipAndCountMissedReleasesAndNeverBurstWhenTheNotifierThreadStalls() {
        // The thread "wakes" 5.3 periods late for release #100: #100..#104 are past saving, #105
        // is 0.3 periods late and still goes out; then the grid continues.
        long stallAtNs = T0_NS + 100 * PERIOD_NS;
        var clock = new ManualClock(T0_NS - PERIOD_NS);
        var kernel = new RecordingKernel(clock);
        kernel.addReceiver(RECEIVER, true);
        var sleeper = new VirtualSleeper(clock, T0_NS + 199 * PERIOD_NS,
                deadline -> deadline == stallAtNs ? 53 * PERIOD_NS / 10 : 0);
        try (var notifier = new Notifier(kernel, CONFIG, clock, sleeper)) {
            notifier.subscribe(Subscription.periodic("loop", RECEIVER, Criticality.HIGH, PERIOD_NS).startingAt(T0_NS));
            notifier.start();
            Await.until(() -> notifier.stats("loop").orElseThrow().toString(), 30_000,
                    () -> notifier.stats("loop").orElseThrow().nextSequence() == 200);

            List<Long> sequences = kernel.ticks().stream().map(Tick::sequence).toList();
            var expected = new ArrayList<Long>();
            for (long k = 0; k < 200; k++) {
                if (k < 100 || k > 104) {
                    expected.add(k);
                }
            }
            assertEquals(expected, sequences);
            assertNoTwoSendsCloserThan(kernel.sentAtNs(), PERIOD_NS / 2);
            SubscriptionStats stats = notifier.stats("loop").orElseThrow();
            assertEquals(5, stats.skippedLate());
            assertEquals(195, stats.ticksSent());
            assertEquals(3 * PERIOD_NS / 10, stats.latenessNs().maxNs(), PERIOD_NS / 100);
        }
    }

    @Test
    void shouldAlsoSkipTheLatestDueReleaseWhenItIsHalfAPeriodLateOrMore() {
        // 5.7 periods late: #105 would go out 0.7 periods late, 0.3 periods before #106.
        long stallAtNs = T0_NS + 100 * PERIOD_NS;
        var clock = new ManualClock(T0_NS - PERIOD_NS);
        var kernel = new RecordingKernel(clock);
        kernel.addReceiver(RECEIVER, true);
        var sleeper = new VirtualSleeper(clock, T0_NS + 199 * PERIOD_NS,
                deadline -> deadline == stallAtNs ? 57 * PERIOD_NS / 10 : 0);
        try (var notifier = new Notifier(kernel, CONFIG, clock, sleeper)) {
            notifier.subscribe(Subscription.periodic("loop", RECEIVER, Criticality.HIGH, PERIOD_NS).startingAt(T0_NS));
            notifier.start();
            Await.until(() -> notifier.stats("loop").orElseThrow().toString(), 30_000,
                    () -> notifier.stats("loop").orElseThrow().nextSequence() == 200);

            List<Long> sequences = kernel.ticks().stream().map(Tick::sequence).toList();
            assertEquals(99L, sequences.get(99));
            assertEquals(106L, sequences.get(100), "the first Tick after the stall is #106, on time");
            assertNoTwoSendsCloserThan(kernel.sentAtNs(), PERIOD_NS / 2);
            assertEquals(6, notifier.stats("loop").orElseThrow().skippedLate());
        }
    }

    @Test
    void shouldSendTheLatestDueReleaseUpToAFullPeriodLateWhenMaxLatenessIsThePeriod() {
        long stallAtNs = T0_NS + 100 * PERIOD_NS;
        var clock = new ManualClock(T0_NS - PERIOD_NS);
        var kernel = new RecordingKernel(clock);
        kernel.addReceiver(RECEIVER, true);
        var sleeper = new VirtualSleeper(clock, T0_NS + 199 * PERIOD_NS,
                deadline -> deadline == stallAtNs ? 57 * PERIOD_NS / 10 : 0);
        try (var notifier = new Notifier(kernel, CONFIG, clock, sleeper)) {
            notifier.subscribe(Subscription.periodic("loop", RECEIVER, Criticality.HIGH, PERIOD_NS).startingAt(T0_NS)
                    .withMaxLatenessNs(PERIOD_NS));
            notifier.start();
            Await.until(() -> notifier.stats("loop").orElseThrow().toString(), 30_000,
                    () -> notifier.stats("loop").orElseThrow().nextSequence() == 200);

            List<Tick> ticks = kernel.ticks();
            assertEquals(105L, ticks.get(100).sequence(), "only the releases before the latest due one are skipped");
            assertEquals(T0_NS + 105 * PERIOD_NS, ticks.get(100).releaseNs());
            assertEquals(5, notifier.stats("loop").orElseThrow().skippedLate());
        }
    }

    @Test
    void shouldServeSeveralSubscriptionsFromOneThreadInReleaseOrder() {
        var clock = new ManualClock(T0_NS - PERIOD_NS);
        var kernel = new RecordingKernel(clock);
        Profile other = Profile.of("logger");
        kernel.addReceiver(RECEIVER, true);
        kernel.addReceiver(other, true);
        var sleeper = new VirtualSleeper(clock, T0_NS + 30 * PERIOD_NS, deadline -> 0);
        try (var notifier = new Notifier(kernel, CONFIG, clock, sleeper)) {
            notifier.subscribe(Subscription.periodic("fast", RECEIVER, Criticality.HIGH, 2 * PERIOD_NS)
                    .startingAt(T0_NS));
            notifier.subscribe(Subscription.periodic("slow", other, Criticality.LOW, 3 * PERIOD_NS).startingAt(T0_NS));
            notifier.start();
            Await.until(() -> kernel.sentCount() + " Ticks sent", 30_000, () -> kernel.sentCount() >= 16 + 11);

            List<Message> sent = kernel.sent();
            long previousReleaseNs = Long.MIN_VALUE;
            for (Message message : sent) {
                long releaseNs = message.contentsAs(Tick.class).releaseNs();
                assertTrue(releaseNs >= previousReleaseNs, "released in time order: " + sent);
                previousReleaseNs = releaseNs;
            }
            // At a common release (every 6 ms) the earlier subscription goes first.
            assertEquals(RECEIVER, sent.get(0).profile());
            assertEquals(other, sent.get(1).profile());
            assertEquals(16, sent.stream().filter(message -> message.profile().equals(RECEIVER)).count());
            assertEquals(11, sent.stream().filter(message -> message.profile().equals(other)).count());
        }
    }

    @Test
    void shouldCarryTheSubscribedQoSSenderAndPeriodOnEveryTick() {
        var clock = new ManualClock(T0_NS - PERIOD_NS);
        var kernel = new RecordingKernel(clock);
        kernel.addReceiver(RECEIVER, true);
        var sleeper = new VirtualSleeper(clock, T0_NS + 4 * 15 * PERIOD_NS, deadline -> 0);
        try (var notifier = new Notifier(kernel, CONFIG, clock, sleeper)) {
            notifier.subscribe(Subscription.periodic("implicit", RECEIVER, Criticality.HIGH, 15 * PERIOD_NS)
                    .startingAt(T0_NS));
            notifier.subscribe(Subscription.periodic("explicit", RECEIVER, Criticality.MIDDLE, 15 * PERIOD_NS)
                    .startingAt(T0_NS).withDeadlineNs(4 * PERIOD_NS).withWcetNs(PERIOD_NS));
            notifier.start();
            Await.until(() -> kernel.sentCount() + " Ticks sent", 30_000, () -> kernel.sentCount() >= 10);

            for (Message message : kernel.sent()) {
                assertEquals(notifier.profile(), message.sender());
                assertEquals(Profile.parse("etherware.notifier[node=test]"), message.sender());
                assertEquals(clock.epochNanos() - clock.nanoTime() + message.contentsAs(Tick.class).releaseNs(),
                        message.timeStamp(), "stamped with the node's epoch time at sending");
                assertEquals(15 * PERIOD_NS, message.contentsAs(Tick.class).periodNs());
            }
            assertEquals(new QoS(Criticality.HIGH, 15 * PERIOD_NS, 15 * PERIOD_NS, 0), kernel.sent().get(0).qos());
            assertEquals(new QoS(Criticality.MIDDLE, 15 * PERIOD_NS, 4 * PERIOD_NS, PERIOD_NS),
                    kernel.sent().get(1).qos());
        }
    }

    @Test
    void shouldReleaseAOneShotOnceAtItsTimeAndThenForgetIt() {
        var clock = new ManualClock(T0_NS - PERIOD_NS);
        var kernel = new RecordingKernel(clock);
        kernel.addReceiver(RECEIVER, true);
        var sleeper = new VirtualSleeper(clock, T0_NS + 100 * PERIOD_NS, deadline -> 0);
        try (var notifier = new Notifier(kernel, CONFIG, clock, sleeper)) {
            Subscription added = notifier.subscribe(
                    Subscription.oneShot("wake-up", RECEIVER, Criticality.MIDDLE, T0_NS + 7 * PERIOD_NS));
            assertTrue(added.isOneShot());
            notifier.start();
            Await.until(() -> "the one-shot to leave", 30_000, () -> notifier.stats("wake-up").isEmpty());

            assertEquals(List.of(new Tick(T0_NS + 7 * PERIOD_NS, 0, 0)), kernel.ticks());
            assertEquals(QoS.of(Criticality.MIDDLE), kernel.sent().getFirst().qos());
            assertEquals(List.of(), notifier.subscriptions());
            // The name is free again.
            notifier.subscribe(Subscription.oneShot("wake-up", RECEIVER, Criticality.MIDDLE, T0_NS + 9 * PERIOD_NS));
            Await.until(() -> kernel.sentCount() + " Ticks sent", 30_000, () -> kernel.sentCount() == 2);
        }
    }

    @Test
    void shouldStartAtTheFirstGridPointNotBeforeNowWhenT0IsPast() {
        var clock = new ManualClock(T0_NS);
        var kernel = new RecordingKernel(clock);
        kernel.addReceiver(RECEIVER, true);
        var sleeper = new VirtualSleeper(clock, T0_NS + 10 * PERIOD_NS, deadline -> 0);
        try (var notifier = new Notifier(kernel, CONFIG, clock, sleeper)) {
            // t0 two and a half periods ago: the phase is kept, nothing counts as skipped.
            notifier.subscribe(Subscription.periodic("phase", RECEIVER, Criticality.HIGH, PERIOD_NS)
                    .startingAt(T0_NS - 5 * PERIOD_NS / 2));
            notifier.start();
            Await.until(() -> kernel.sentCount() + " Ticks sent", 30_000, () -> kernel.sentCount() >= 10);

            Tick first = kernel.ticks().getFirst();
            assertEquals(new Tick(T0_NS + PERIOD_NS / 2, 3, PERIOD_NS), first);
            assertEquals(0, notifier.stats("phase").orElseThrow().skippedReleases());
        }
    }

    private static void assertNoTwoSendsCloserThan(List<Long> sentAtNs, long minimumGapNs) {
        for (int i = 1; i < sentAtNs.size(); i++) {
            long gapNs = sentAtNs.get(i) - sentAtNs.get(i - 1);
            assertTrue(gapNs >= minimumGapNs, "Ticks #" + (i - 1) + " and #" + i + " went out " + gapNs
                    + " ns apart: a burst");
        }
    }
}
