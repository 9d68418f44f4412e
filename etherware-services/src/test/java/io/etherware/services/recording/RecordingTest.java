package io.etherware.services.recording;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import example.counter.Seq;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.testkit.Await;
import java.io.DataOutputStream;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Arrays;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * Recording the messages to chosen profiles and replaying them into another node: the same
 * messages, in the same order, with their QoS; a damaged file is refused with a message that
 * names the record and what is wrong.
 */
class RecordingTest {

    private static final Profile SENSOR = Profile.parse("sensor[id=1]");
    private static final Profile OTHER = Profile.parse("other");
    private static final List<Criticality> LEVELS = List.of(Criticality.HIGH, Criticality.MIDDLE, Criticality.LOW,
            Criticality.NONE);

    @TempDir
    Path dir;

    private static ContentsTypes types() {
        return new ContentsTypes().register("test.seq", Seq.class);
    }

    /** A started node whose sensor (and other) component collects what it handles. */
    private static EtherwareNode node(String id, List<Message> sensed) {
        var node = EtherwareNode.builder().nodeId(id).contentsTypes(types()).build();
        node.add(SENSOR, () -> (message, context) -> sensed.add(message));
        node.add(OTHER, () -> (message, context) -> { });
        return node.start();
    }

    @Test
    void shouldReplayTheRecordedMessagesInOrderWithTheirQos() throws Exception {
        Path file = dir.resolve("run.ewrec");
        var sensed = new CopyOnWriteArrayList<Message>();
        try (var node = node("rec-a", sensed)) {
            try (var recorder = Recorder.start(node, file, List.of(Profile.parse("sensor")))) {
                for (int i = 0; i < 200; i++) {
                    node.send(SENSOR, new Seq(i), QoS.of(LEVELS.get(i % LEVELS.size())));
                    node.send(OTHER, new Seq(-i)); // not chosen
                }
                Await.until("the sensor handled 200", () -> sensed.size() == 200);
                recorder.close();
                assertEquals(200, recorder.recorded());
                assertEquals(0, recorder.dropped() + recorder.unencodable());
            }
        }

        Recording recording = Recording.read(file, types());
        assertEquals("rec-a", recording.nodeId());
        assertEquals(200, recording.messages().size());
        long last = 0;
        for (int i = 0; i < 200; i++) {
            Recording.Recorded recorded = recording.messages().get(i);
            assertEquals(new Seq(i), recorded.message().contents());
            assertEquals(SENSOR, recorded.message().profile());
            assertEquals(LEVELS.get(i % LEVELS.size()), recorded.message().qos().criticality());
            assertTrue(recorded.offsetNs() >= last, "offsets never go back");
            last = recorded.offsetNs();
        }

        var replayed = new CopyOnWriteArrayList<Message>();
        try (var other = node("rec-b", replayed)) {
            assertEquals(200, recording.replay(other, 1_000.0));
            Await.until("the replayed 200 handled", () -> replayed.size() == 200);
        }
        // One dispatcher (the default FIFO scheduler): handled in the order sent.
        for (int i = 0; i < 200; i++) {
            assertEquals(new Seq(i), replayed.get(i).contents());
            assertEquals(LEVELS.get(i % LEVELS.size()), replayed.get(i).qos().criticality());
        }
    }

    @Test
    void shouldRefuseAFileThatIsNotARecordingOrIsDamaged() throws Exception {
        Path file = dir.resolve("run.ewrec");
        try (var node = node("rec-c", new CopyOnWriteArrayList<>());
             var recorder = Recorder.start(node, file, List.of(SENSOR))) {
            for (int i = 0; i < 3; i++) {
                node.send(SENSOR, new Seq(i));
            }
            Await.until("three recorded", () -> recorder.recorded() == 3);
        }
        byte[] whole = Files.readAllBytes(file);

        Path text = dir.resolve("notes.txt");
        Files.writeString(text, "hello");
        var notRecording = assertThrows(IOException.class, () -> Recording.read(text, types()));
        assertTrue(notRecording.getMessage().contains("is not an Etherware recording"), notRecording.getMessage());

        Path cut = dir.resolve("cut.ewrec");
        Files.write(cut, Arrays.copyOf(whole, whole.length - 5));
        var truncated = assertThrows(IOException.class, () -> Recording.read(cut, types()));
        assertTrue(truncated.getMessage().contains("record 3 at byte") && truncated.getMessage().contains("truncated"),
                truncated.getMessage());

        Path huge = dir.resolve("huge.ewrec");
        byte[] bad = whole.clone();
        int firstRecord = RecordingFormat.FIXED_HEADER_BYTES + "rec-c".length();
        bad[firstRecord + 8] = 0x7f; // the first record's length, now about 2 GB
        Files.write(huge, bad);
        var tooLong = assertThrows(IOException.class, () -> Recording.read(huge, types()));
        assertTrue(tooLong.getMessage().contains("record 1 at byte " + firstRecord + " has length"),
                tooLong.getMessage());

        var unknown = assertThrows(IOException.class, () -> Recording.read(file, new ContentsTypes()));
        assertTrue(unknown.getMessage().contains("record 1") && unknown.getMessage().contains("does not decode"),
                unknown.getMessage());

        Path version = dir.resolve("version.ewrec");
        try (var out = new DataOutputStream(Files.newOutputStream(version))) {
            out.write(RecordingFormat.MAGIC);
            out.writeShort(9);
        }
        var newer = assertThrows(IOException.class, () -> Recording.read(version, types()));
        assertTrue(newer.getMessage().contains("format version 9"), newer.getMessage());
    }

    @Test
    void shouldRunTheReadmeExample() throws Exception {
        Path file = dir.resolve("run.ewrec");
        var sensed = new CopyOnWriteArrayList<Message>();
        try (var node = node("readme-a", new CopyOnWriteArrayList<>()); var other = node("readme-b", sensed)) {
            // README example begins
            try (Recorder recorder = Recorder.start(node, file, List.of(Profile.parse("sensor")))) {
                node.send(Profile.parse("sensor[id=1]"), new Seq(1), QoS.of(Criticality.HIGH)); // recorded as it passes
                assertTrue(recorder.file().equals(file));
            }
            Recording recording = Recording.read(file, other.contentsTypes());
            recording.replay(other, 1.0); // the same messages, at the recorded pace, on this thread
            // README example ends
            Await.until("the replayed message handled", () -> sensed.size() == 1);
            assertEquals(new Seq(1), sensed.getFirst().contents());
        }
    }

    @Test
    void shouldRefuseToRecordNothingAndToReplayAtAPointlessSpeed() throws Exception {
        try (var node = node("rec-d", new CopyOnWriteArrayList<>())) {
            assertThrows(IllegalArgumentException.class, () -> Recorder.start(node, dir.resolve("x"), List.of()));
            try (var recorder = Recorder.start(node, dir.resolve("empty.ewrec"), List.of(SENSOR))) {
                assertEquals(0, recorder.recorded());
            }
            Recording empty = Recording.read(dir.resolve("empty.ewrec"), types());
            assertEquals(0, empty.messages().size());
            assertThrows(IllegalArgumentException.class, () -> empty.replay(node, 0));
            assertThrows(IllegalArgumentException.class, () -> empty.replay(node, Double.NaN));
        }
    }
}
