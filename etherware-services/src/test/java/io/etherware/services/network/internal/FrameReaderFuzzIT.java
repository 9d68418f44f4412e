package io.etherware.services.network.internal;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import com.code_intelligence.jazzer.junit.FuzzTest;
import io.etherware.services.network.NetworkConfig;
import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.EOFException;
import java.io.IOException;
import java.util.ArrayList;
import java.util.HexFormat;
import java.util.List;
import org.junit.jupiter.api.Timeout;

/**
 * Whatever a peer sends, {@link FrameReader} reads a HELLO and then frames, and fails only with a
 * {@link ProtocolException} that names a reason or with an {@link EOFException}; every frame it
 * returns is one {@link FrameWriter} writes back to the same frame.
 *
 * <p>A Jazzer {@link FuzzTest}: in a normal build it only replays the seed corpus in
 * {@code src/test/resources/io/etherware/services/network/internal/FrameReaderFuzzITInputs/};
 * to fuzz, see "Fuzzing" in the README.
 */
class FrameReaderFuzzIT {

    /** Fuzz inputs beyond this are skipped. */
    private static final int MAX_INPUT_BYTES = 64 * 1024;
    /** The smallest limit a node accepts, so that oversize frames are among the inputs. */
    private static final int MAX_FRAME_BYTES = NetworkConfig.MIN_FRAME_BYTES;
    /** {@link FrameWriter} shortens longer REJECT and BYE reasons. */
    private static final int MAX_REASON_CHARS = 1000;

    @Timeout(10)
    @FuzzTest(maxDuration = "30s")
    void shouldReadFramesOrRefuseCleanlyWhateverThePeerSends(byte[] input) throws IOException {
        if (input.length > MAX_INPUT_BYTES) {
            return;
        }
        var reader = new FrameReader(new ByteArrayInputStream(input), MAX_FRAME_BYTES);
        List<Frame> frames = new ArrayList<>();
        try {
            frames.add(reader.readHello());
            // Ends: every frame takes at least 5 bytes of the input.
            while (true) {
                frames.add(reader.next());
            }
        } catch (ProtocolException refused) {
            assertNotNull(refused.reason(), "a refusal names its close reason");
            assertTrue(refused.getMessage() != null && !refused.getMessage().isBlank(), "a refusal says why");
        } catch (EOFException ended) {
            // The input ended, between frames or inside one.
        }
        // Any other exception fails the test: that is a finding.
        for (Frame frame : frames) {
            requireWrittenBackTheSame(frame, input);
        }
    }

    private static void requireWrittenBackTheSame(Frame frame, byte[] input) throws IOException {
        if (frame instanceof Frame.Reject(long seq, String reason) && reason.length() > MAX_REASON_CHARS
                || frame instanceof Frame.Bye(int code, String text) && text.length() > MAX_REASON_CHARS) {
            return;
        }
        var bytes = new ByteArrayOutputStream();
        var writer = new FrameWriter(bytes);
        switch (frame) {
            case Frame.Hello hello -> writer.hello(hello);
            case Frame.Resume resume -> writer.resume(resume);
            case Frame.Data data -> writer.data(data.seq(), data.ack(), data.hops(), data.xml());
            case Frame.Ack ack -> writer.ack(ack.count());
            case Frame.Heartbeat heartbeat -> writer.heartbeat();
            case Frame.Sync sync -> writer.sync();
            case Frame.Announce announce -> writer.announce(FrameWriter.announceBody(announce.version(),
                    announce.profiles()));
            case Frame.TimeRequest request -> writer.timeRequest(request.t1());
            case Frame.TimeReply reply -> writer.timeReply(reply.t1(), reply.t2(), reply.t3());
            case Frame.Reject reject -> writer.reject(reject.seq(), reject.reason());
            case Frame.Bye bye -> writer.bye(bye.code(), bye.text());
        }
        writer.flush();
        var again = new FrameReader(new ByteArrayInputStream(bytes.toByteArray()), MAX_FRAME_BYTES);
        String where = "frame " + frame + " read from " + HexFormat.of().formatHex(input);
        if (frame instanceof Frame.Hello) {
            assertEquals(frame, again.readHello(), where);
        } else if (frame instanceof Frame.Data data) {
            var copy = (Frame.Data) again.next();
            assertEquals(List.of(data.seq(), data.ack(), (long) data.hops()),
                    List.of(copy.seq(), copy.ack(), (long) copy.hops()), where);
            assertArrayEquals(data.xml(), copy.xml(), where);
        } else {
            assertEquals(frame, again.next(), where);
        }
    }
}
