package io.etherware.core.codec;

import io.etherware.core.codec.TestContents.Angles;
import io.etherware.core.codec.TestContents.CounterState;
import io.etherware.core.codec.TestContents.Everything;
import io.etherware.core.codec.TestContents.Holder;
import io.etherware.core.codec.TestContents.Mode;
import io.etherware.core.codec.TestContents.Point;
import io.etherware.core.codec.TestContents.Samples;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Empty;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.message.Tick;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.Arguments;
import org.junit.jupiter.params.provider.MethodSource;
import org.xml.sax.SAXException;

import java.io.IOException;
import java.io.InputStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Arrays;
import java.util.List;
import java.util.stream.Stream;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.fail;

/**
 * Messages whose exact XML is checked in under {@code src/test/resources/.../golden}, so the
 * wire format cannot drift silently. After a deliberate format change, rewrite them with
 * {@code ./mvnw -pl etherware-core test -Dtest=MessageCodecGoldenTest -Detherware.golden.update=true},
 * review the diff, update WIRE-FORMAT.md and the XSD, and run again without the flag.
 */
class MessageCodecGoldenTest {

    private static final String DIRECTORY = "io/etherware/core/codec/golden/";

    private final MessageCodec codec = MessageCodec.builder().contentsTypes(TestContents.registry()).build();

    static Stream<Arguments> goldenMessages() {
        return Stream.of(
                golden("tick", new Message(Profile.parse("controller[car=1]"), Profile.parse("notifier"),
                        1_732_233_600_000_000_000L, QoS.periodic(Criticality.HIGH, 15_000_000),
                        new Tick(8_123_456_789L, 42, 15_000_000), new MessageId("node1", 1042), null)),
                golden("text-reply", new Message(Profile.parse("console"), null, 1_732_233_600_123_456_789L, QoS.NONE,
                        new Text("a < b && c > d; ]]> stays text\r\nline two\ttab \uD83D\uDE00 Ω"),
                        new MessageId("node-2", 7), new MessageId("node1", 1042))),
                golden("empty", new Message(Profile.parse("supervisor[node=node1,level=2]"), null, 0, QoS.of(Criticality.LOW),
                        Empty.INSTANCE, new MessageId("n", 0), null)),
                golden("angles", new Message(Profile.parse("controller[car=1]"), Profile.parse("dsp-proxy[car=1]"),
                        1_732_233_600_015_000_000L, new QoS(Criticality.HIGH, 15_000_000, 12_000_000, 2_000_000),
                        new Angles(1001, -2048, 513, 15_015_000), new MessageId("node1", 3), null)),
                golden("holder", new Message(Profile.parse("migrator"), null, 5, QoS.of(Criticality.MIDDLE),
                        new Holder(null, new CounterState(12, "twelve"),
                                Arrays.asList(new Tick(1, 2, 3), null, Empty.INSTANCE, new Text(""))),
                        new MessageId("node1", 4), null)),
                golden("everything", new Message(Profile.parse("sink"), null, -1, QoS.NONE,
                        new Everything(true, (byte) -8, (short) 300, 'é', -5, Long.MIN_VALUE, 0.1f, -0.0,
                                null, 7, null, Double.NaN, '<', " padded ", Mode.RUNNING,
                                Profile.parse("controller[car=1]"), new MessageId("node1", 9), new Point(1.5, -2.25),
                                List.of(new Point(0, 1e-300)), Arrays.asList("a", null, ""), List.of(1L, -1L),
                                List.of(List.of(), List.of(1, 2)), List.of(Mode.IDLE, Mode.FAULT)),
                        new MessageId("node1", 5), null)),
                golden("samples", new Message(Profile.parse("recorder"), null, 9, QoS.NONE,
                        new Samples(new double[]{0.25, Double.POSITIVE_INFINITY, Double.NEGATIVE_INFINITY, 1e21},
                                new long[]{-1, 0, Long.MAX_VALUE}, new int[0], new byte[]{1, 2, 3, -1}),
                        new MessageId("node1", 6), null)));
    }

    @ParameterizedTest(name = "{0}")
    @MethodSource("goldenMessages")
    void shouldEncodeExactlyTheCheckedInDocument(String name, Message message) throws IOException {
        byte[] encoded = codec.encode(message);
        if (Boolean.getBoolean("etherware.golden.update")) {
            Path file = Path.of("src/test/resources", DIRECTORY, name + ".xml");
            Files.write(file, encoded);
            fail("rewrote " + file.toAbsolutePath() + "; review the diff, then run again without etherware.golden.update");
        }
        assertEquals(new String(golden(name), StandardCharsets.UTF_8), new String(encoded, StandardCharsets.UTF_8));
    }

    @ParameterizedTest(name = "{0}")
    @MethodSource("goldenMessages")
    void shouldDecodeTheCheckedInDocumentToTheMessage(String name, Message message) throws IOException, SAXException {
        byte[] document = golden(name);
        assertEquals(message, codec.decode(document));
        Schemas.validate(document);
    }

    private static Arguments golden(String name, Message message) {
        return Arguments.of(name, message);
    }

    private static byte[] golden(String name) throws IOException {
        try (InputStream in = MessageCodecGoldenTest.class.getClassLoader().getResourceAsStream(DIRECTORY + name + ".xml")) {
            assertNotNull(in, "golden file " + DIRECTORY + name + ".xml");
            return in.readAllBytes();
        }
    }
}
