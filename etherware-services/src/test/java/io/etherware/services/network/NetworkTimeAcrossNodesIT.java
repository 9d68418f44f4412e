package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Profile;
import io.etherware.core.time.NodeClock;
import io.etherware.services.time.PeerTime;
import java.time.Duration;
import java.time.Instant;
import java.util.concurrent.ConcurrentLinkedQueue;
import org.junit.jupiter.api.Test;

/**
 * NetworkTime between two nodes, one of whose clocks is 2.5 s ahead and runs 50 ppm fast: the
 * estimate and the translated time stamps against the truth, which the test knows exactly.
 */
class NetworkTimeAcrossNodesIT {

    private static final long OFFSET_NS = 2_500_000_000L;
    private static final double DRIFT_PPM = 50;

    /** The system clock, offset and drifting from the moment it was made. */
    private static final class SkewedClock implements NodeClock {
        final long originNs = System.nanoTime();

        @Override
        public long nanoTime() {
            return System.nanoTime();
        }

        @Override
        public long epochNanos() {
            Instant now = Instant.now();
            return now.getEpochSecond() * 1_000_000_000L + now.getNano() + trueOffsetNs();
        }

        long trueOffsetNs() {
            return OFFSET_NS + Math.round(DRIFT_PPM * 1e-6 * (System.nanoTime() - originNs));
        }
    }

    @Test
    void shouldEstimateAnOffsetClockWithinAMillisecondAndTranslateTimeStamps() throws Exception {
        var skewed = new SkewedClock();
        var lateness = new ConcurrentLinkedQueue<Long>();
        try (var b = TestNode.start("b", skewed, TestNode.config().timeProbes(Duration.ofMillis(100), 8), node -> node);
             var a = TestNode.start("a", TestNode.config().peer(b.address()))) {
            a.node.add(Profile.of("sink"), () -> (message, context) ->
                    lateness.add(context.clock().epochNanos() - message.timeStamp()));
            assertTrue(b.net.awaitResolvable(Profile.of("sink"), Duration.ofSeconds(30)));
            long worstErrorNs = 0;
            long worstSettledErrorNs = 0;
            long settledNs = System.nanoTime() + Duration.ofSeconds(1).toNanos();
            long endNs = System.nanoTime() + Duration.ofSeconds(3).toNanos();
            while (System.nanoTime() < endNs) {
                b.node.send(Profile.of("sink"), new Num(1));
                Thread.sleep(20);
                PeerTime estimate = a.net.networkTime().peer("b").orElseThrow();
                long errorNs = Math.abs(estimate.offsetAt(a.node.clock().epochNanos()) - skewed.trueOffsetNs());
                worstErrorNs = Math.max(worstErrorNs, errorNs);
                if (System.nanoTime() > settledNs) {
                    worstSettledErrorNs = Math.max(worstSettledErrorNs, errorNs);
                }
            }
            PeerTime finalEstimate = a.net.networkTime().peer("b").orElseThrow();
            PeerTime reverse = b.net.networkTime().peer("a").orElseThrow();
            long reverseErrorNs = Math.abs(reverse.offsetAt(b.node.clock().epochNanos()) + skewed.trueOffsetNs());
            long worstLatenessNs = lateness.stream().mapToLong(Math::abs).max().orElseThrow();
            System.out.printf("NetworkTime over loopback, peer +2.5 s drifting 50 ppm: worst offset error %d us over 3 s,"
                            + " %d us after the first second (final: offset error %d us, uncertainty %d us, drift %.1f ppm, %d samples; reverse"
                            + " error %d us); worst |arrival - translated time stamp| %d us over %d messages%n",
                    worstErrorNs / 1000, worstSettledErrorNs / 1000, Math.abs(finalEstimate.offsetAt(a.node.clock().epochNanos())
                            - skewed.trueOffsetNs()) / 1000, finalEstimate.uncertaintyNs() / 1000,
                    finalEstimate.driftPpm(), finalEstimate.samples(), reverseErrorNs / 1000, worstLatenessNs / 1000,
                    lateness.size());
            assertTrue(finalEstimate.isMeasured());
            // Within a millisecond once the first burst has settled (after 1 s); during the burst on a
            // loaded machine one slow round trip can hold a first estimate off by more (half its time).
            assertTrue(worstSettledErrorNs < 1_000_000, "worst error after the first second " + worstSettledErrorNs
                    + " ns");
            assertTrue(worstErrorNs < 10_000_000, "worst error " + worstErrorNs + " ns");
            assertTrue(reverseErrorNs < 1_000_000, "reverse error " + reverseErrorNs + " ns");
            // Untranslated, the time stamps would be 2.5 s in the future; translated, they are a
            // delivery latency ago (a loaded box may delay a handler, not by a second), give or take
            // the estimate's error, which the first burst's messages carry too (bounded above).
            assertTrue(lateness.size() > 50);
            assertTrue(lateness.stream().allMatch(ns -> ns > -10_000_000 && ns < 1_000_000_000), lateness.toString());
        }
    }
}
