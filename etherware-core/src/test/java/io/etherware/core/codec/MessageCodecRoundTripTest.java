package io.etherware.core.codec;

import io.etherware.core.codec.TestContents.Holder;
import io.etherware.core.codec.TestContents.LogLine;
import io.etherware.core.codec.TestContents.Node;
import io.etherware.core.codec.TestContents.Samples;
import io.etherware.core.codec.TestContents.Typed;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Empty;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.message.Tick;
import org.junit.jupiter.api.Test;
import org.xml.sax.SAXException;

import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** Round trips of chosen messages; {@link MessageCodecRoundTripIT} round-trips thousands of generated ones. */
class MessageCodecRoundTripTest {

    static final long SEED = 0x5EED_2026L;

    private final MessageCodec codec = MessageCodec.builder().contentsTypes(TestContents.registry()).build();

    @Test
    void shouldRoundTripEveryQosCombination() {
        List<QoS> all = MessageGenerator.allQosCombinations();
        assertEquals(32, all.size());
        for (QoS qos : all) {
            Message message = message(qos, Empty.INSTANCE);
            assertEquals(qos, codec.decode(codec.encode(message)).qos());
        }
    }

    @Test
    void shouldOmitUnspecifiedDurationsWhenQosHasNone() {
        String document = codec.encodeToString(message(QoS.of(Criticality.LOW), Empty.INSTANCE));
        assertTrue(document.contains("<qos><criticality>LOW</criticality></qos>"), document);
        String periodic = codec.encodeToString(message(QoS.periodic(Criticality.HIGH, 15_000_000), Empty.INSTANCE));
        assertTrue(periodic.contains("<periodNs>15000000</periodNs><deadlineNs>15000000</deadlineNs></qos>"), periodic);
    }

    @Test
    void shouldKeepXmlSpecialCharactersWhenTextHasThem() {
        for (String text : List.of("]]>", "a]]>b]]]]>", "&", "&amp;", "<", "<message>", "\"'", "\r", "\r\n", "a\rb",
                "\n", "\t", " lead and trail ", "   ", "", "\uD83D\uDE00", "x\uDBFF\uDFFFy", "\u00A0\u2028", "&#13;")) {
            Message message = message(QoS.NONE, new Text(text));
            byte[] document = codec.encode(message);
            assertEquals(text, ((Text) codec.decode(document).contents()).text(), () -> "as " + utf8(document));
        }
    }

    @Test
    void shouldEncodeCarriageReturnAsCharacterReferenceSoReadersKeepIt() {
        String document = codec.encodeToString(message(QoS.NONE, new Text("a\r\nb")));
        assertTrue(document.contains("<text>a&#xd;\nb</text>"), document);
    }

    @Test
    void shouldDistinguishNullFromEmptyWhenFieldsAreOptional() {
        var empty = new LogLine("", "");
        var nulls = new LogLine(null, null);
        assertEquals(empty, codec.decode(codec.encode(message(QoS.NONE, empty))).contents());
        assertEquals(nulls, codec.decode(codec.encode(message(QoS.NONE, nulls))).contents());
        assertTrue(codec.encodeToString(message(QoS.NONE, nulls)).contains("xsi:nil=\"true\""));
    }

    @Test
    void shouldRoundTripPolymorphicFieldsThroughTheRegistry() {
        var holder = new Holder(new Tick(1, 2, 3), new TestContents.CounterState(-7, "s"),
                Arrays.asList(Empty.INSTANCE, null, new Text("t"), new TestContents.Angles(1, 2, 3, 4)));
        byte[] document = codec.encode(message(QoS.NONE, holder));
        assertEquals(holder, codec.decode(document).contents());
        String xml = utf8(document);
        assertTrue(xml.contains("<state type=\"counter-state\">"), xml);
        assertTrue(xml.contains("<item type=\"angles\">"), xml);
        assertTrue(!xml.contains("io.etherware") && !xml.contains("TestContents"), "no class name on the wire: " + xml);
    }

    @Test
    void shouldRoundTripArraysExactlyWhenTheyHoldSpecialValues() {
        var samples = new Samples(new double[]{0.0, -0.0, Double.NaN, Double.POSITIVE_INFINITY,
                Double.NEGATIVE_INFINITY, Double.MIN_VALUE, Double.MAX_VALUE, 0.1},
                new long[]{Long.MIN_VALUE, 0, Long.MAX_VALUE}, new int[]{Integer.MIN_VALUE, -1, Integer.MAX_VALUE},
                new byte[]{0, -1, 127, -128});
        Samples decoded = (Samples) codec.decode(codec.encode(message(QoS.NONE, samples))).contents();
        assertEquals(samples, decoded);
        assertEquals(Double.doubleToRawLongBits(-0.0), Double.doubleToRawLongBits(decoded.values()[1]));
        var empty = new Samples(new double[0], new long[0], new int[0], new byte[0]);
        assertEquals(empty, codec.decode(codec.encode(message(QoS.NONE, empty))).contents());
        var nulls = new Samples(null, null, null, null);
        assertEquals(nulls, codec.decode(codec.encode(message(QoS.NONE, nulls))).contents());
    }

    @Test
    void shouldReadTheTypeAttributeAndATypeFieldApartWhenARecordHasBoth() {
        var typed = new Typed("tick", 5);
        assertEquals(typed, codec.decode(codec.encode(message(QoS.NONE, typed))).contents());
    }

    @Test
    void shouldRoundTripEnvelopeExtremesWhenFieldsAreAtTheirLimits() {
        var attributes = new java.util.LinkedHashMap<String, String>();
        attributes.put("z", "1");
        attributes.put("a", "x:/@+-._");
        var message = new Message(new Profile("r_0.-", attributes), Profile.of("s"), Long.MIN_VALUE,
                new QoS(Criticality.HIGH, Long.MAX_VALUE, 1, Long.MAX_VALUE), Empty.INSTANCE,
                new MessageId("n", Long.MAX_VALUE), new MessageId("0", 0));
        Message decoded = codec.decode(codec.encode(message));
        assertEquals(message, decoded);
        assertEquals(List.of("z", "a"), new ArrayList<>(decoded.profile().attributes().keySet()),
                "attribute order survives");
    }

    @Test
    void shouldRoundTripLargePayloadsWhenTheyFitTheLimits() throws SAXException {
        var generator = new MessageGenerator(SEED + 1);
        var big = new StringBuilder();
        while (big.length() < MessageCodec.DEFAULT_MAX_TEXT_LENGTH - 100) {
            big.append(generator.text(1));
        }
        String text = big.substring(0, MessageCodec.DEFAULT_MAX_TEXT_LENGTH - 100);
        if (Character.isHighSurrogate(text.charAt(text.length() - 1))) {
            text = text.substring(0, text.length() - 1);
        }
        Message bigText = message(QoS.NONE, new Text(text));
        byte[] document = codec.encode(bigText);
        assertTrue(document.length > 500_000, "large: " + document.length);
        assertEquals(bigText, codec.decode(document));
        Schemas.validate(document);

        Message manySamples = message(QoS.NONE, generator.samples(8_000));
        byte[] samplesDocument = codec.encode(manySamples);
        assertTrue(samplesDocument.length > 200_000, "large: " + samplesDocument.length);
        assertEquals(manySamples, codec.decode(samplesDocument));
    }

    @Test
    void shouldDecodeAsMessageWhenARecordFieldIsNamedMessage() throws SAXException {
        // With processContents="lax" the schema would check <message>hi</message> as an envelope.
        Message message = message(QoS.NONE, new LogLine("hi", "INFO"));
        byte[] document = codec.encode(message);
        assertEquals(message, codec.decode(document));
        Schemas.validate(document);
    }

    @Test
    void shouldAcceptIndentationAndAnyElementOrderWhenAPeerWroteIt() {
        String document = """
                <?xml version="1.0" encoding="UTF-8"?>
                <!-- written by hand -->
                <message version="1">
                  <contents type="tick">
                    <periodNs> 15000000 </periodNs>
                    <releaseNs>5</releaseNs>
                    <sequence>2</sequence>
                  </contents>
                  <messageId>peer#9</messageId>
                  <qos>
                    <deadlineNs>1000</deadlineNs>
                    <criticality>MIDDLE</criticality>
                  </qos>
                  <timeStamp>42</timeStamp>
                  <profile>controller[car=1]</profile>
                </message>
                """;
        Message expected = new Message(Profile.parse("controller[car=1]"), null, 42,
                new QoS(Criticality.MIDDLE, 0, 1000, 0), new Tick(5, 2, 15_000_000), MessageId.parse("peer#9"), null);
        assertEquals(expected, codec.decode(document));
        assertEquals(expected, codec.decode(document.getBytes(StandardCharsets.UTF_8)));
    }

    @Test
    void shouldProduceTheSameDocumentWhenEncodedAgainAfterDecoding() {
        var generator = new MessageGenerator(SEED + 2);
        for (int i = 0; i < 200; i++) {
            byte[] first = codec.encode(generator.message(i));
            assertArrayEquals(first, codec.encode(codec.decode(first)));
        }
    }

    @Test
    void shouldDecodeRecursiveContentsWhenWithinTheDepthLimit() {
        Node chain = Node.chain(20);
        assertEquals(chain, codec.decode(codec.encode(message(QoS.NONE, chain))).contents());
        assertNotEquals(Node.chain(19), chain);
    }

    static Message message(QoS qos, Contents contents) {
        return new Message(Profile.parse("controller[car=1]"), null, 1_732_233_600_000_000_000L, qos, contents,
                new MessageId("node1", 1), null);
    }

    static String utf8(byte[] document) {
        return new String(document, StandardCharsets.UTF_8);
    }
}
