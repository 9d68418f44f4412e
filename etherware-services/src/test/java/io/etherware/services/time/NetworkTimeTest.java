package io.etherware.services.time;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.time.NodeClock;
import java.time.Duration;
import java.util.SplittableRandom;
import org.junit.jupiter.api.Test;

/**
 * The filter on simulated exchanges: exact clocks and chosen path delays, so the error against
 * the truth is known and the test is deterministic.
 */
class NetworkTimeTest {

    private static final long SECOND_NS = 1_000_000_000L;
    private static final long BASE_LOCAL_NS = 1_750_000_000L * SECOND_NS;
    private static final NodeClock UNUSED_CLOCK = NodeClock.system();

    /** A peer clock: offset by a constant plus a drift, as a function of local time. */
    private record PeerClock(long offsetNs, double driftPpm) {
        long at(long localNs) {
            return localNs + offsetNs + Math.round(driftPpm * 1e-6 * (localNs - BASE_LOCAL_NS));
        }

        long trueOffsetAt(long localNs) {
            return at(localNs) - localNs;
        }
    }

    /** One exchange starting at local time {@code t1} with the given one-way delays. */
    private static TimeSample exchange(PeerClock peer, long t1, long outNs, long turnaroundNs, long backNs) {
        long arriveLocal = t1 + outNs;
        long leaveLocal = arriveLocal + turnaroundNs;
        return new TimeSample(t1, peer.at(arriveLocal), peer.at(leaveLocal), leaveLocal + backNs);
    }

    @Test
    void shouldComputeOffsetAndRoundTripOfOneExchange() {
        var peer = new PeerClock(2_500_000_000L, 0);
        TimeSample sample = exchange(peer, BASE_LOCAL_NS, 30_000, 5_000, 30_000);
        assertEquals(2_500_000_000L, sample.offsetNs());
        assertEquals(60_000, sample.roundTripNs());
        // Asymmetry moves the offset by half the difference, within half the round trip.
        TimeSample skewed = exchange(peer, BASE_LOCAL_NS, 50_000, 5_000, 10_000);
        assertEquals(2_500_000_000L + 20_000, skewed.offsetNs());
        assertTrue(Math.abs(skewed.offsetNs() - peer.offsetNs()) <= skewed.roundTripNs() / 2);
    }

    @Test
    void shouldTrustTheMinimumDelayExchangeOverLateOnes() {
        var time = new NetworkTime(UNUSED_CLOCK, 8, Duration.ofSeconds(1));
        var peer = new PeerClock(-7_000_000L, 0);
        long t = BASE_LOCAL_NS;
        time.onExchange("b", exchange(peer, t, 4_000_000, 10_000, 100_000)); // queued behind data
        time.onExchange("b", exchange(peer, t += 100_000_000, 40_000, 10_000, 40_000));
        PeerTime estimate = time.onExchange("b", exchange(peer, t += 100_000_000, 100_000, 10_000, 3_000_000))
                .orElseThrow();
        assertEquals(-7_000_000L, estimate.offsetNs());
        assertEquals(80_000, estimate.roundTripNs());
        assertEquals(40_000, estimate.uncertaintyNs());
        assertEquals(3, estimate.samples());
    }

    @Test
    void shouldStayWithinAMillisecondOfAPeerOffsetByTwoAndAHalfSecondsDriftingFiftyPpm() {
        var time = new NetworkTime(UNUSED_CLOCK);
        var peer = new PeerClock(2_500_000_000L, 50);
        var random = new SplittableRandom(5);
        long worstAfterFirstNs = 0;
        long worstOnceFittedNs = 0;
        long t = BASE_LOCAL_NS;
        for (int second = 0; second < 300; second++, t += SECOND_NS) {
            // A loaded LAN: 20-220 us each way, independently, and one exchange in ten stuck 5 ms
            // behind other traffic in one direction.
            long out = 20_000 + random.nextLong(200_000) + (random.nextInt(10) == 0 ? 5_000_000 : 0);
            long back = 20_000 + random.nextLong(200_000);
            PeerTime estimate = time.onExchange("b", exchange(peer, t, out, 15_000, back)).orElseThrow();
            // Checked half a period later, when the estimate is the stalest it gets.
            long checkNs = t + SECOND_NS / 2;
            long errorNs = Math.abs(estimate.offsetAt(checkNs) - peer.trueOffsetAt(checkNs));
            worstAfterFirstNs = Math.max(worstAfterFirstNs, errorNs);
            if (second >= NetworkTime.DEFAULT_WINDOW_SIZE) {
                worstOnceFittedNs = Math.max(worstOnceFittedNs, errorNs);
                assertEquals(50, estimate.driftPpm(), 15, "drift at second " + second);
            }
        }
        System.out.printf("simulated 50 ppm peer: worst error %d ns, %d ns once fitted%n", worstAfterFirstNs, worstOnceFittedNs);
        assertTrue(worstAfterFirstNs < 1_000_000, "worst error " + worstAfterFirstNs + " ns");
        assertTrue(worstOnceFittedNs < 150_000, "worst error once the drift is fitted " + worstOnceFittedNs + " ns");
    }

    @Test
    void shouldTranslateAMessageTimeStampIntoTheLocalClock() {
        var time = new NetworkTime(UNUSED_CLOCK);
        var peer = new PeerClock(2_500_000_000L, 0);
        var message = new Message(Profile.of("x"), null, peer.at(BASE_LOCAL_NS), QoS.NONE, new Text("t"),
                new MessageId("b", 1), null);
        assertEquals(message, time.toLocal("b", message), "unknown peers are left alone");
        time.onExchange("b", exchange(peer, BASE_LOCAL_NS - SECOND_NS, 30_000, 5_000, 30_000));
        assertEquals(BASE_LOCAL_NS, time.toLocal("b", message).timeStamp());
        assertEquals(message.withTimeStamp(BASE_LOCAL_NS), time.toLocal("b", message));
    }

    @Test
    void shouldGuessFromTheHandshakeUntilTheFirstExchange() {
        var time = new NetworkTime(UNUSED_CLOCK);
        time.onHandshake("b", BASE_LOCAL_NS + 1_000_050_000L, BASE_LOCAL_NS);
        PeerTime guess = time.peer("b").orElseThrow();
        assertFalse(guess.isMeasured());
        assertEquals(1_000_050_000L, guess.offsetNs());
        assertEquals(-1, guess.uncertaintyNs());
        var peer = new PeerClock(1_000_000_000L, 0);
        time.onExchange("b", exchange(peer, BASE_LOCAL_NS, 30_000, 5_000, 30_000));
        time.onHandshake("b", BASE_LOCAL_NS, BASE_LOCAL_NS); // a later guess does not override a measurement
        assertEquals(1_000_000_000L, time.peer("b").orElseThrow().offsetNs());
        time.forget("b");
        assertTrue(time.peer("b").isEmpty());
    }

    @Test
    void shouldIgnoreAnExchangeWithANegativeRoundTrip() {
        var time = new NetworkTime(UNUSED_CLOCK);
        assertTrue(time.onExchange("b", new TimeSample(100, 0, 1_000, 200)).isEmpty());
        assertTrue(time.peer("b").isEmpty());
    }

    @Test
    void shouldRefuseAWindowOutOfRange() {
        var error = org.junit.jupiter.api.Assertions.assertThrows(IllegalArgumentException.class,
                () -> new NetworkTime(UNUSED_CLOCK, 0, Duration.ofSeconds(1)));
        assertTrue(error.getMessage().startsWith("windowSize=0"), error.getMessage());
    }
}
