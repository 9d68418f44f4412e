package io.etherware.services.notifier;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.DispatcherSpec;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import io.etherware.testkit.ManualClock;
import org.junit.jupiter.api.Test;

/** Configuration and subscription values: defaults, derivation, and errors that name the field. */
class NotifierConfigTest {

    private static final Profile TARGET = Profile.of("controller");

    @Test
    void shouldRequestSchedFifoTwoAboveTableIIWithoutSpinByDefault() {
        NotifierConfig config = NotifierConfig.defaults();
        assertEquals(ThreadPolicy.fifo(82), config.threadPolicy(), "above the network's threads at 81");
        assertEquals(0, config.spinNs());
        assertEquals(config, NotifierConfig.above(ThreadSchedulingRule.tableII()));
    }

    @Test
    void shouldSitTwoAboveTheHighestRealtimeDispatcherOfARule() {
        var rule = ThreadSchedulingRule.of(DispatcherSpec.nonRealtime(), DispatcherSpec.fifo(40),
                DispatcherSpec.fifo(90));
        assertEquals(ThreadPolicy.fifo(92), NotifierConfig.above(rule).threadPolicy());
        assertEquals(ThreadPolicy.fifo(99), NotifierConfig.above(ThreadSchedulingRule.of(DispatcherSpec.fifo(99)))
                .threadPolicy(), "capped at 99");
        assertEquals(ThreadPolicy.NON_REALTIME, NotifierConfig.above(ThreadSchedulingRule.nonRealtime(2))
                .threadPolicy());
    }

    @Test
    void shouldRefuseAnUnboundedSpinOrAnOutOfRangePriorityNamingTheField() {
        var spin = assertThrows(IllegalArgumentException.class, () -> NotifierConfig.defaults().withSpin(java.time.Duration.ofNanos(200_000)));
        assertTrue(spin.getMessage().startsWith("spinNs=200000 must be in 0..100000"), spin.getMessage());
        var priority = assertThrows(IllegalArgumentException.class,
                () -> NotifierConfig.defaults().withThreadPolicy(ThreadPolicy.fifo(100)));
        assertTrue(priority.getMessage().startsWith("threadPolicy.priority=100"), priority.getMessage());
        assertThrows(IllegalArgumentException.class, () -> NotifierConfig.defaults().withThreadName(" "));
    }

    @Test
    void shouldDefaultThePeriodicDeadlineToThePeriodAndTheLatenessLimitToHalfOfIt() {
        Subscription subscription = Subscription.periodic("loop", TARGET, Criticality.HIGH, 15_000_000);
        assertEquals(QoS.periodic(Criticality.HIGH, 15_000_000), subscription.qos());
        assertEquals(7_500_000, subscription.maxLatenessNs());
        assertEquals(Subscription.UNSET, subscription.firstReleaseNs());
        assertTrue(subscription.backPressure());
        Subscription oneShot = Subscription.oneShot("once", TARGET, Criticality.LOW, 42);
        assertTrue(oneShot.isOneShot());
        assertEquals(0, oneShot.maxLatenessNs());
    }

    @Test
    void shouldRefuseBadSubscriptionsNamingTheField() {
        var period = assertThrows(IllegalArgumentException.class,
                () -> Subscription.periodic("loop", TARGET, Criticality.HIGH, 0));
        assertTrue(period.getMessage().contains("periodNs=0"), period.getMessage());
        var lateness = assertThrows(IllegalArgumentException.class,
                () -> Subscription.periodic("loop", TARGET, Criticality.HIGH, 1_000).withMaxLatenessNs(1_001));
        assertTrue(lateness.getMessage().contains("maxLatenessNs=1001 must be in 1..periodNs=1000"),
                lateness.getMessage());
        var name = assertThrows(IllegalArgumentException.class,
                () -> Subscription.periodic("a\nb", TARGET, Criticality.HIGH, 1_000));
        assertTrue(name.getMessage().contains("control characters"), name.getMessage());
        assertThrows(IllegalArgumentException.class, () -> Subscription.periodic("", TARGET, Criticality.HIGH, 1));
        assertThrows(NullPointerException.class, () -> Subscription.periodic("loop", null, Criticality.HIGH, 1));
    }

    @Test
    void shouldRefuseADuplicateNameAndSubscriptionsAfterClose() {
        var kernel = new RecordingKernel(new ManualClock(0));
        var notifier = new Notifier(kernel, NotifierConfig.defaults());
        notifier.subscribe(Subscription.periodic("loop", TARGET, Criticality.HIGH, 1_000));
        var duplicate = assertThrows(IllegalArgumentException.class,
                () -> notifier.subscribe(Subscription.periodic("loop", TARGET, Criticality.LOW, 2_000)));
        assertTrue(duplicate.getMessage().contains("'loop' is already in use"), duplicate.getMessage());
        var unknown = assertThrows(IllegalArgumentException.class, () -> notifier.retarget("nope", TARGET));
        assertTrue(unknown.getMessage().contains("'nope'"), unknown.getMessage());
        notifier.close();
        assertThrows(IllegalStateException.class,
                () -> notifier.subscribe(Subscription.periodic("other", TARGET, Criticality.HIGH, 1_000)));
        assertThrows(IllegalStateException.class, notifier::start);
    }
}
