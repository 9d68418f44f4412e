package io.etherware.services.network.internal;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Profile;
import io.etherware.services.network.CloseReason;
import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.EOFException;
import java.io.IOException;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.util.Arrays;
import java.util.List;
import org.junit.jupiter.api.Test;

/** Frames written by {@link FrameWriter} read back by {@link FrameReader}, and what it refuses. */
class FramesTest {

    @FunctionalInterface
    private interface Writing {
        void write(FrameWriter writer) throws IOException;
    }

    private static FrameReader readerOf(Writing writing) throws IOException {
        var bytes = new ByteArrayOutputStream();
        var writer = new FrameWriter(bytes);
        writing.write(writer);
        writer.flush();
        return new FrameReader(new ByteArrayInputStream(bytes.toByteArray()), 1 << 20);
    }

    @Test
    void shouldReadBackEveryFrameItWrote() throws IOException {
        byte[] xml = "<message/>".getBytes(StandardCharsets.UTF_8);
        List<Profile> profiles = List.of(Profile.of("etherware.node", "id", "b"), Profile.parse("ctrl[car=1]"));
        FrameReader reader = readerOf(writer -> {
            writer.hello(new Frame.Hello(Frame.VERSION, "node-1", 42, 1_700_000_000_000_000_000L, 1 << 20, 2, 1));
            writer.resume(new Frame.Resume(7, 8, 9));
            writer.data(3, 2, 1, xml);
            writer.ack(11);
            writer.heartbeat();
            writer.announce(FrameWriter.announceBody(5, profiles));
            writer.timeRequest(100);
            writer.timeReply(100, 200, 300);
            writer.reject(3, "bad");
            writer.bye(CloseReason.DUPLICATE.code(), "keeping the other, é");
        });
        assertEquals(new Frame.Hello(Frame.VERSION, "node-1", 42, 1_700_000_000_000_000_000L, 1 << 20, 2, 1), reader.readHello());
        assertEquals(new Frame.Resume(7, 8, 9), reader.next());
        var data = assertInstanceOf(Frame.Data.class, reader.next());
        assertEquals(3, data.seq());
        assertEquals(2, data.ack());
        assertEquals(1, data.hops());
        assertArrayEquals(xml, data.xml());
        assertEquals(new Frame.Ack(11), reader.next());
        assertEquals(Frame.Heartbeat.INSTANCE, reader.next());
        assertEquals(new Frame.Announce(5, profiles), reader.next());
        assertEquals(new Frame.TimeRequest(100), reader.next());
        assertEquals(new Frame.TimeReply(100, 200, 300), reader.next());
        assertEquals(new Frame.Reject(3, "bad"), reader.next());
        assertEquals(new Frame.Bye(CloseReason.DUPLICATE.code(), "keeping the other, é"), reader.next());
        assertThrows(EOFException.class, reader::next);
    }

    private static ProtocolException refused(byte[] bytes) {
        var reader = new FrameReader(new ByteArrayInputStream(bytes), 4096);
        return assertThrows(ProtocolException.class, reader::next);
    }

    @Test
    void shouldRefuseMalformedFramesNamingWhatIsWrong() {
        var zeroLength = refused(new byte[] {0, 0, 0, 0});
        assertEquals(CloseReason.MALFORMED_FRAME, zeroLength.reason());
        var oversize = refused(new byte[] {0, 0, 0x10, 0x01, Frame.DATA});
        assertEquals(CloseReason.OVERSIZE_FRAME, oversize.reason());
        assertTrue(oversize.getMessage().contains("4097"), oversize.getMessage());
        var shortAck = refused(new byte[] {0, 0, 0, 3, Frame.ACK, 1, 2});
        assertTrue(shortAck.getMessage().contains("ACK body of 2 bytes"), shortAck.getMessage());
        var shortData = refused(new byte[] {0, 0, 0, 3, Frame.DATA, 1, 2});
        assertEquals(CloseReason.MALFORMED_FRAME, shortData.reason());
        var hugeCount = refused(new byte[] {0, 0, 0, 13, Frame.ANNOUNCE, 0, 0, 0, 0, 0, 0, 0, 1, 0x7f, 0, 0, 0});
        assertTrue(hugeCount.getMessage().contains("claims"), hugeCount.getMessage());
        var badUtf8 = refused(new byte[] {0, 0, 0, 5, Frame.BYE, 1, 0, 1, (byte) 0xff});
        assertTrue(badUtf8.getMessage().contains("UTF-8"), badUtf8.getMessage());
        var trailing = refused(new byte[] {0, 0, 0, 5, Frame.BYE, 1, 0, 0, 9});
        assertTrue(trailing.getMessage().contains("trailing"), trailing.getMessage());
        var secondHello = refused(new byte[] {0, 0, 0, 1, Frame.HELLO});
        assertTrue(secondHello.getMessage().contains("second HELLO"), secondHello.getMessage());
    }

    @Test
    void shouldRefuseAFirstFrameThatIsNoHello() {
        byte[] resumeFirst = new byte[29];
        resumeFirst[3] = 25;
        resumeFirst[4] = Frame.RESUME;
        var reader = new FrameReader(new ByteArrayInputStream(resumeFirst), 4096);
        var error = assertThrows(ProtocolException.class, reader::readHello);
        assertEquals(CloseReason.BAD_HANDSHAKE, error.reason());
        byte[] truncated = Arrays.copyOf(new byte[] {0, 0, 0, 40, Frame.HELLO, 0x45, 0x57}, 7);
        assertThrows(EOFException.class, new FrameReader(new ByteArrayInputStream(truncated), 4096)::readHello);
    }

    @Test
    void shouldRefuseAHelloTooShortForItsFields() {
        // A frame as long as the smallest HELLO, but its node id takes 5 of the 22 bytes that
        // incarnation, clock, maxFrameBytes, lanes and lane need.
        var bytes = ByteBuffer.allocate(4 + 32).putInt(32).put(Frame.HELLO).putInt(Frame.MAGIC)
                .putShort((short) Frame.VERSION).putShort((short) 6).put("node-1".getBytes(StandardCharsets.UTF_8));
        var reader = new FrameReader(new ByteArrayInputStream(bytes.array()), 4096);
        var error = assertThrows(ProtocolException.class, reader::readHello);
        assertEquals(CloseReason.BAD_HANDSHAKE, error.reason());
        assertTrue(error.getMessage().contains("HELLO frame of 32 bytes is too short"), error.getMessage());
    }
}
