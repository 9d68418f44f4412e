package io.etherware.rt.stats;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import org.junit.jupiter.api.Test;

class LatencyRecorderTest {

    private static final long MAX_NS = 1_000_000_000L;

    @Test
    void shouldKeepEverySampleAcrossSnapshotsWhenReadRepeatedly() {
        var recorder = new LatencyRecorder(MAX_NS, 3);
        recorder.record(1_000);
        recorder.record(2_000);
        LatencySnapshot first = recorder.snapshot();
        recorder.record(3_000);
        LatencySnapshot second = recorder.snapshot();

        assertEquals(2, first.count());
        assertEquals(2_000, first.maxNs(), 2);
        assertEquals(3, second.count(), "a snapshot holds everything since the recorder was made");
        assertEquals(1_000, second.minNs(), 1);
        assertEquals(3_000, second.maxNs(), 3);
        assertEquals(2_000, second.meanNs(), 3);
        assertEquals(2_000, second.percentileNs(50), 2);
        assertEquals(2, first.count(), "an earlier snapshot does not change");
    }

    @Test
    void shouldClampSamplesToTheTrackableRangeWhenOutOfIt() {
        var recorder = new LatencyRecorder(MAX_NS, 2);
        recorder.record(-5);
        recorder.record(10 * MAX_NS);
        LatencySnapshot snapshot = recorder.snapshot();

        assertEquals(2, snapshot.count());
        assertEquals(0, snapshot.minNs());
        assertEquals(MAX_NS, snapshot.maxNs(), MAX_NS / 100);
        assertEquals(MAX_NS, snapshot.highestTrackableNs());
    }

    @Test
    void shouldAddSamplesToACopyWhenAskedForMore() {
        var recorder = new LatencyRecorder(MAX_NS, 3);
        for (int i = 0; i < 98; i++) {
            recorder.record(1_000);
        }
        LatencySnapshot measured = recorder.snapshot();
        LatencySnapshot withSkipped = measured.withSamples(500_000, 2);

        assertEquals(98, measured.count());
        assertEquals(1_000, measured.percentileNs(99), 1);
        assertEquals(100, withSkipped.count());
        assertEquals(500_000, withSkipped.percentileNs(99), 500);
        assertNotEquals(measured, withSkipped);
        assertEquals(measured, measured.withSamples(500_000, 0));
    }

    @Test
    void shouldReportZerosWhenNothingWasRecorded() {
        LatencySnapshot empty = new LatencyRecorder(MAX_NS, 2).snapshot();

        assertEquals(0, empty.count());
        assertEquals(0, empty.maxNs());
        assertEquals(0, empty.percentileNs(99.9));
    }

    @Test
    void shouldRejectMisuseWithTheFieldAndValue() {
        var snapshot = new LatencyRecorder(MAX_NS, 2).snapshot();

        var percentile = assertThrows(IllegalArgumentException.class, () -> snapshot.percentileNs(101));
        assertEquals("percentile=101.0: must be within [0, 100]", percentile.getMessage());
        assertThrows(IllegalArgumentException.class, () -> snapshot.percentileNs(Double.NaN));
        assertThrows(IllegalArgumentException.class, () -> snapshot.withSamples(1, -1));
        var digits = assertThrows(IllegalArgumentException.class, () -> new LatencyRecorder(MAX_NS, 6));
        assertEquals("significantDigits=6: must be within [0, 5]", digits.getMessage());
        assertThrows(IllegalArgumentException.class, () -> new LatencyRecorder(1, 2));
    }
}
