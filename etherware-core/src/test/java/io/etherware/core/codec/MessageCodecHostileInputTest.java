package io.etherware.core.codec;

import io.etherware.core.message.Message;
import io.etherware.core.message.MessageFormatException;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.message.Tick;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.Arguments;
import org.junit.jupiter.params.provider.MethodSource;

import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.SocketTimeoutException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Arrays;
import java.util.stream.Stream;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A corpus of bad and hostile documents, each rejected with a message that says what was wrong. */
class MessageCodecHostileInputTest {

    private static final String ENVELOPE = "<message version=\"1\"><profile>controller[car=1]</profile>"
            + "<timeStamp>1</timeStamp><qos><criticality>HIGH</criticality></qos><messageId>n#1</messageId>";
    private static final String TICK = "<contents type=\"tick\"><releaseNs>1</releaseNs><sequence>2</sequence>"
            + "<periodNs>3</periodNs></contents>";

    private final MessageCodec codec = MessageCodec.builder().contentsTypes(TestContents.registry()).build();

    static Stream<Arguments> badDocuments() {
        byte[] valid = utf8(ENVELOPE + TICK + "</message>");
        return Stream.of(
                bad("truncated document", Arrays.copyOf(valid, valid.length / 2), "truncated"),
                bad("truncated before the end tag", Arrays.copyOf(valid, valid.length - 3), "truncated"),
                bad("empty document", new byte[0], "truncated or empty"),
                bad("not XML at all", utf8("hello"), "malformed XML"),
                bad("wrong root", utf8("<msg><profile>x</profile></msg>"), "root element is <msg>"),
                bad("root in a namespace", utf8("<message xmlns=\"urn:x\"/>"), "root element is <message> in namespace 'urn:x'"),
                bad("text instead of elements", utf8("<message>hello</message>"), "unexpected text 'hello' in <message>"),
                bad("missing profile", utf8(ENVELOPE.replace("<profile>controller[car=1]</profile>", "") + TICK
                        + "</message>"), "<message> has no <profile>"),
                bad("missing contents", utf8(ENVELOPE + "</message>"), "<message> has no <contents>"),
                bad("nil profile", utf8(ENVELOPE.replace("<profile>controller[car=1]</profile>",
                        "<profile xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" xsi:nil=\"true\"/>") + TICK
                        + "</message>"), "<profile> must not be nil"),
                bad("malformed profile text", envelopeWith("<profile>controller[car=1]</profile>",
                        "<profile>controller[car=1</profile>"), "malformed <profile>: profile 'controller[car=1'"),
                bad("profile attribute without value", envelopeWith("<profile>controller[car=1]</profile>",
                        "<profile>controller[car]</profile>"), "is not key=value"),
                bad("duplicate profile", envelopeWith("<profile>controller[car=1]</profile>",
                        "<profile>a</profile><profile>b</profile>"), "<profile> appears twice"),
                bad("malformed message id", envelopeWith("<messageId>n#1</messageId>", "<messageId>n#one</messageId>"),
                        "malformed <messageId>"),
                bad("malformed time stamp", envelopeWith("<timeStamp>1</timeStamp>", "<timeStamp>soon</timeStamp>"),
                        "malformed <timeStamp>: 'soon' is not a long"),
                bad("negative period", envelopeWith("<criticality>HIGH</criticality>",
                        "<criticality>HIGH</criticality><periodNs>-5</periodNs>"), "periodNs=-5 must not be negative"),
                bad("zero deadline", envelopeWith("<criticality>HIGH</criticality>",
                        "<criticality>HIGH</criticality><deadlineNs>0</deadlineNs>"),
                        "<deadlineNs> is 0: a duration that is present must be > 0"),
                bad("unknown criticality", envelopeWith("<criticality>HIGH</criticality>",
                        "<criticality>URGENT</criticality>"), "criticality 'URGENT' is not one of"),
                bad("qos without criticality", envelopeWith("<criticality>HIGH</criticality>", ""),
                        "<qos> has no <criticality>"),
                bad("unsupported version", envelopeWith("version=\"1\"", "version=\"2\""),
                        "unsupported wire format version '2'"),
                bad("unknown envelope element", envelopeWith("<timeStamp>1</timeStamp>",
                        "<timeStamp>1</timeStamp><priority>9</priority>"), "unexpected element <priority> in <message>"),
                bad("unknown contents type", contents("<contents type=\"tock\"><n>1</n></contents>"),
                        "unknown contents type 'tock'; registered types are ["),
                bad("class name as contents type", contents("<contents type=\"io.etherware.core.message.Tick\"/>"),
                        "unknown contents type 'io.etherware.core.message.Tick'"),
                bad("contents without type", contents("<contents><releaseNs>1</releaseNs></contents>"),
                        "<contents> has no type attribute"),
                bad("payload field of the wrong type", contents(TICK.replace("<sequence>2<", "<sequence>two<")),
                        "contents type 'tick': field 'sequence': 'two' is not a long"),
                bad("payload int out of range", contents("<contents type=\"angles\"><sequence>1</sequence>"
                        + "<encoder1>4294967296</encoder1><encoder2>0</encoder2><dspTimeUs>0</dspTimeUs></contents>"),
                        "contents type 'angles': field 'encoder1': '4294967296' is not an int"),
                bad("payload field missing", contents(TICK.replace("<periodNs>3</periodNs>", "")),
                        "contents type 'tick': missing field 'periodNs'"),
                bad("payload field unknown", contents(TICK.replace("<periodNs>", "<bogus/><periodNs>")),
                        "contents type 'tick': Tick has no field 'bogus'"),
                bad("payload field twice", contents(TICK.replace("<periodNs>", "<sequence>3</sequence><periodNs>")),
                        "field 'sequence' appears twice"),
                bad("payload rejected by the record", contents(TICK.replace("<sequence>2<", "<sequence>-2<")),
                        "contents type 'tick': invalid Tick: sequence=-2 must be >= 0"),
                bad("nil for a primitive", contents(TICK.replace("<sequence>2</sequence>",
                        "<sequence xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" xsi:nil=\"true\"/>")),
                        "field 'sequence': nil is not allowed for a long"),
                bad("child elements where text belongs", contents(TICK.replace("<sequence>2</sequence>",
                        "<sequence><n>2</n></sequence>")), "field 'sequence': expected text for a long"),
                bad("text mixed into contents", contents(TICK.replace("<releaseNs>", "junk<releaseNs>")),
                        "unexpected text 'junk'"),
                bad("polymorphic field of the wrong interface", contents("<contents type=\"holder\"><any "
                        + "type=\"empty\"/><state type=\"tick\"><releaseNs>1</releaseNs><sequence>2</sequence>"
                        + "<periodNs>3</periodNs></state><many/></contents>"),
                        "contents type 'holder': field 'state': contents type 'tick' is a Tick, which is not a ComponentState"),
                bad("polymorphic field of an unknown type", contents("<contents type=\"holder\"><any type=\"evil\"/>"
                        + "<state type=\"counter-state\"><count>1</count><label>x</label></state><many/></contents>"),
                        "field 'any': unknown contents type 'evil'"),
                bad("polymorphic field without type", contents("<contents type=\"holder\"><any/>"
                        + "<state type=\"counter-state\"><count>1</count><label>x</label></state><many/></contents>"),
                        "field 'any': has no type attribute"),
                bad("bad list entry", contents("<contents type=\"holder\"><any type=\"empty\"/>"
                        + "<state type=\"counter-state\"><count>1</count><label>x</label></state>"
                        + "<many><item type=\"empty\"/><item type=\"text\"/></many></contents>"),
                        "field 'many[1]': missing field 'text'"),
                bad("list with a foreign element", contents("<contents type=\"holder\"><any type=\"empty\"/>"
                        + "<state type=\"counter-state\"><count>1</count><label>x</label></state>"
                        + "<many><entry type=\"empty\"/></many></contents>"), "expected <item> elements"),
                bad("base64 with a foreign character", contents("<contents type=\"samples\"><values/><stampsNs/>"
                        + "<counts/><raw>AQ!D</raw></contents>"), "field 'raw': is not base64"),
                bad("array entry of the wrong type", contents("<contents type=\"samples\"><values>1.5 2,5</values>"
                        + "<stampsNs/><counts/><raw/></contents>"), "field 'values': entry 1 '2,5' is not a double"),
                bad("U+FFFE in text", contents("<contents type=\"text\"><text>a\uFFFE</text></contents>"),
                        "not allowed in XML 1.0"),
                bad("U+FFFF as a char", contents("<contents type=\"everything\"><c>\uFFFF</c></contents>"),
                        "not allowed in XML 1.0"),
                bad("second root", utf8(ENVELOPE + TICK + "</message><message/>"), "multiple roots"),
                bad("nil message", utf8("<message xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
                        + "xsi:nil=\"true\"/>"), "<message> must not be nil"),
                bad("nil message before a second root", utf8("<message xmlns:xsi=\"http://www.w3.org/2001/"
                        + "XMLSchema-instance\" xsi:nil=\"true\"/>" + ENVELOPE + TICK + "</message>"),
                        "<message> must not be nil"),
                bad("undeclared entity", contents(TICK.replace("<sequence>2<", "<sequence>&two;<")),
                        "Undeclared general entity"),
                bad("null character reference", contents(TICK.replace("<sequence>2<", "<sequence>&#0;<")),
                        "malformed XML"),
                bad("raw control character", contents(TICK.replace("<sequence>2<", "<sequence>\u0001<")),
                        "malformed XML"),
                bad("invalid UTF-8 continuation byte", withBytesInText(0xC3, 0x28), "not valid UTF-8 (messages are UTF-8): "
                        + "byte 0x28 at offset 179: invalid continuation byte"),
                bad("invalid UTF-8 start byte", withBytesInText(0xFF), "byte 0xFF at offset 178: invalid start byte"),
                bad("lone UTF-8 continuation byte", withBytesInText(0x80), "byte 0x80 at offset 178: invalid start byte"),
                bad("overlong two-byte UTF-8", withBytesInText(0xC0, 0xAF), "byte 0xC0 at offset 178: overlong encoding"),
                bad("overlong '<' in UTF-8", withBytesInText(0xC0, 0xBC), "byte 0xC0 at offset 178: overlong encoding"),
                bad("overlong three-byte UTF-8", withBytesInText(0xE0, 0x80, 0xAF), "not valid UTF-8"),
                bad("UTF-8 surrogate", withBytesInText(0xED, 0xA0, 0x80), "not valid UTF-8"),
                bad("UTF-8 above U+10FFFF", withBytesInText(0xF4, 0x90, 0x80, 0x80), "not valid UTF-8"),
                bad("UTF-8 sequence cut by the end", Arrays.copyOf(withBytesInText(0xE2, 0x82, 0xAC),
                        utf8(ENVELOPE + "<contents type=\"text\"><text>a").length + 2),
                        "byte 0xE2 at offset 178: sequence truncated by the end of the document"),
                bad("declared Latin-1", utf8("<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>" + ENVELOPE + TICK
                        + "</message>"), "encoding 'ISO-8859-1' is not accepted; messages are UTF-8"),
                bad("UTF-16", utf16(ENVELOPE + TICK + "</message>"), "messages are UTF-8"),
                bad("billion laughs", utf8(billionLaughs()), "DOCTYPE is not allowed"),
                bad("internal entity", utf8("<!DOCTYPE message [<!ENTITY p \"controller\">]>"
                        + ENVELOPE.replace("controller[car=1]", "&p;") + TICK + "</message>"), "DOCTYPE is not allowed"),
                bad("nesting past the limit", deepNodes(40), "nested deeper than maxNestingDepth=64"),
                bad("nesting past the limit where no element is expected", contents("<contents type=\"text\"><text>"
                        + "<a>".repeat(100) + "</a>".repeat(100) + "</text></contents>"), "expected text for a String"));
    }

    @ParameterizedTest(name = "{0}")
    @MethodSource("badDocuments")
    void shouldRejectWithAClearMessageWhenTheDocumentIsBad(String name, byte[] document, String expected) {
        var error = assertThrows(MessageFormatException.class, () -> codec.decode(document));
        assertEquals(MessageFormatException.class, error.getClass());
        assertTrue(error.getMessage().contains(expected),
                () -> name + ": expected '" + expected + "' in: " + error.getMessage());
        // Nothing else is lost: the codec goes on decoding good messages.
        assertEquals(new Tick(1, 2, 3), codec.decode(utf8(ENVELOPE + TICK + "</message>")).contents());
    }

    @ParameterizedTest(name = "{0}")
    @MethodSource("badDocuments")
    void shouldRejectTheSameWayWhenTheDocumentIsAString(String name, byte[] document, String expected) {
        if (name.contains("UTF") || expected.contains("UTF-8")) {
            return; // bytes-only cases: a String has no encoding
        }
        String text = new String(document, StandardCharsets.UTF_8);
        var error = assertThrows(MessageFormatException.class, () -> codec.decode(text));
        assertTrue(error.getMessage().contains(expected),
                () -> name + ": expected '" + expected + "' in: " + error.getMessage());
    }

    @Test
    void shouldRejectUnpairedSurrogatesWhenTheDocumentIsAString() {
        for (String text : new String[]{"\uD800", "x\uDC00", "\uDBFFx"}) {
            String document = new String(contents("<contents type=\"text\"><text>" + "</text></contents>"),
                    StandardCharsets.UTF_8).replace("<text></text>", "<text>" + text + "</text>");
            var error = assertThrows(MessageFormatException.class, () -> codec.decode(document));
            assertTrue(error.getMessage().contains("is not allowed in XML 1.0"), error.getMessage());
        }
    }

    @Test
    void shouldNeverReadTheFileWhenAnExternalEntityPointsAtIt(@TempDir Path directory) throws IOException {
        String marker = "MARKER-" + System.nanoTime();
        Path secret = Files.writeString(directory.resolve("secret.txt"), marker);
        String uri = secret.toUri().toString();
        for (String document : new String[]{
                "<!DOCTYPE message [<!ENTITY xxe SYSTEM \"" + uri + "\">]>" + ENVELOPE
                        + "<contents type=\"text\"><text>&xxe;</text></contents></message>",
                "<!DOCTYPE message [<!ENTITY % xxe SYSTEM \"" + uri + "\"> %xxe;]>" + ENVELOPE + TICK + "</message>",
                "<!DOCTYPE message SYSTEM \"" + uri + "\">" + ENVELOPE + TICK + "</message>"}) {
            var error = assertThrows(MessageFormatException.class, () -> codec.decode(utf8(document)));
            assertTrue(error.getMessage().contains("DOCTYPE"), error.getMessage());
            for (Throwable t = error; t != null; t = t.getCause()) {
                assertFalse(String.valueOf(t.getMessage()).contains(marker), "the file was read: " + t.getMessage());
            }
        }
    }

    @Test
    void shouldNeverFetchAUrlWhenAnExternalEntityPointsAtIt() throws IOException {
        try (var server = new ServerSocket(0, 8, InetAddress.getLoopbackAddress())) {
            String url = "http://127.0.0.1:" + server.getLocalPort() + "/evil.dtd";
            for (String document : new String[]{
                    "<!DOCTYPE message SYSTEM \"" + url + "\">" + ENVELOPE + TICK + "</message>",
                    "<!DOCTYPE message [<!ENTITY xxe SYSTEM \"" + url + "\">]>" + ENVELOPE
                            + "<contents type=\"text\"><text>&xxe;</text></contents></message>"}) {
                var error = assertThrows(MessageFormatException.class, () -> codec.decode(utf8(document)));
                assertTrue(error.getMessage().contains("DOCTYPE"), error.getMessage());
            }
            // Had the parser connected, the connection would already wait in the backlog.
            server.setSoTimeout(200);
            assertThrows(SocketTimeoutException.class, server::accept, "the parser connected to the URL");
        }
    }

    @Test
    void shouldRejectOversizeDocumentsBeforeParsingThem() {
        MessageCodec small = MessageCodec.builder().contentsTypes(TestContents.registry()).maxDocumentBytes(4096).build();
        byte[] oversize = utf8(ENVELOPE + "<contents type=\"text\"><text>" + "x".repeat(5000) + "</text></contents></message>");
        var error = assertThrows(MessageFormatException.class, () -> small.decode(oversize));
        assertTrue(error.getMessage().contains("bytes is over maxDocumentBytes=4096"), error.getMessage());
        var stringError = assertThrows(MessageFormatException.class, () -> small.decode(new String(oversize, StandardCharsets.UTF_8)));
        assertTrue(stringError.getMessage().contains("chars is over maxDocumentBytes=4096"), stringError.getMessage());

        byte[] overDefault = new byte[MessageCodec.DEFAULT_MAX_DOCUMENT_BYTES + 1];
        var defaultError = assertThrows(MessageFormatException.class, () -> codec.decode(overDefault));
        assertTrue(defaultError.getMessage().contains("over maxDocumentBytes=1048576"), defaultError.getMessage());
    }

    @Test
    void shouldRejectLongTextAndAttributesWhenOverTheTextLimit() {
        MessageCodec strict = MessageCodec.builder().contentsTypes(TestContents.registry()).maxTextLength(100).build();
        var text = assertThrows(MessageFormatException.class, () -> strict.decode(
                contents("<contents type=\"text\"><text>" + "y".repeat(200) + "</text></contents>")));
        assertTrue(text.getMessage().contains("longer than maxTextLength=100"), text.getMessage());
        var split = assertThrows(MessageFormatException.class, () -> strict.decode(
                contents("<contents type=\"text\"><text>" + "y".repeat(60) + "<![CDATA[" + "z".repeat(60)
                        + "]]></text></contents>")));
        assertTrue(split.getMessage().contains("longer than maxTextLength=100"), split.getMessage());
        var attribute = assertThrows(MessageFormatException.class, () -> strict.decode(
                contents("<contents type=\"" + "t".repeat(200) + "\"/>")));
        assertTrue(attribute.getMessage().contains("longer than maxTextLength=100"), attribute.getMessage());
        Message fits = MessageCodecRoundTripTest.message(QoS.NONE, new Text("y".repeat(100)));
        assertEquals(fits, strict.decode(strict.encode(fits)));
    }

    @Test
    void shouldHonourAConfiguredNestingLimit() {
        MessageCodec shallow = MessageCodec.builder().contentsTypes(TestContents.registry()).maxNestingDepth(5).build();
        Message fits = MessageCodecRoundTripTest.message(QoS.NONE, TestContents.Node.chain(1));
        assertEquals(fits, shallow.decode(shallow.encode(fits)));
        byte[] deep = codec.encode(MessageCodecRoundTripTest.message(QoS.NONE, TestContents.Node.chain(3)));
        var error = assertThrows(MessageFormatException.class, () -> shallow.decode(deep));
        assertTrue(error.getMessage().contains("nested deeper than maxNestingDepth=5"), error.getMessage());
    }

    private static Arguments bad(String name, byte[] document, String expected) {
        return Arguments.of(name, document, expected);
    }

    private static byte[] deepNodes(int depth) {
        MessageCodec permissive = MessageCodec.builder().contentsTypes(TestContents.registry()).maxNestingDepth(1000).build();
        return permissive.encode(MessageCodecRoundTripTest.message(QoS.NONE, TestContents.Node.chain(depth)));
    }

    private static byte[] envelopeWith(String original, String replacement) {
        if (!ENVELOPE.contains(original)) {
            throw new IllegalArgumentException(original);
        }
        return utf8(ENVELOPE.replace(original, replacement) + TICK + "</message>");
    }

    private static byte[] contents(String contents) {
        return utf8(ENVELOPE + contents + "</message>");
    }

    private static byte[] withBytesInText(int... bytes) {
        byte[] head = utf8(ENVELOPE + "<contents type=\"text\"><text>a");
        byte[] tail = utf8("b</text></contents></message>");
        byte[] document = Arrays.copyOf(head, head.length + bytes.length + tail.length);
        for (int i = 0; i < bytes.length; i++) {
            document[head.length + i] = (byte) bytes[i];
        }
        System.arraycopy(tail, 0, document, head.length + bytes.length, tail.length);
        return document;
    }

    private static String billionLaughs() {
        var dtd = new StringBuilder("<!DOCTYPE message [<!ENTITY lol \"lol\">");
        for (int i = 1; i <= 9; i++) {
            dtd.append("<!ENTITY lol").append(i).append(" \"").append(("&lol" + (i == 1 ? "" : i - 1) + ";").repeat(10))
                    .append("\">");
        }
        return dtd.append("]>") + ENVELOPE + "<contents type=\"text\"><text>&lol9;</text></contents></message>";
    }

    private static byte[] utf8(String text) {
        return text.getBytes(StandardCharsets.UTF_8);
    }

    private static byte[] utf16(String text) {
        return text.getBytes(StandardCharsets.UTF_16);
    }
}
