package io.etherware.core.codec;

import io.etherware.core.codec.TestContents.Everything;
import io.etherware.core.codec.TestContents.Holder;
import io.etherware.core.codec.TestContents.Node;
import io.etherware.core.codec.TestContents.Unregistered;
import io.etherware.core.codec.TestContents.WithMap;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Empty;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageFormatException;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.message.Tick;
import org.junit.jupiter.api.Test;

import java.util.Arrays;
import java.util.List;
import java.util.Map;

import static io.etherware.core.codec.MessageCodecRoundTripTest.message;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** What the encoder refuses, and how the codec is configured. */
class MessageCodecEncodeTest {

    private final MessageCodec codec = MessageCodec.builder().contentsTypes(TestContents.registry()).build();

    @Test
    void shouldRefuseContentsWhoseTypeIsNotRegistered() {
        String error = encodeError(codec, message(QoS.NONE, new Unregistered(1)));
        assertTrue(error.startsWith("cannot encode message node1#1: contents type "), error);
        assertTrue(error.contains("Unregistered is not registered"), error);
    }

    @Test
    void shouldRefuseANestedContentsWhoseTypeIsNotRegistered() {
        var holder = new Holder(new Unregistered(1), new TestContents.CounterState(1, "x"), List.of());
        String error = encodeError(codec, message(QoS.NONE, holder));
        assertTrue(error.contains("contents type 'holder': field 'any': contents type "), error);
    }

    @Test
    void shouldNameTheRecordAndComponentWhenAFieldTypeCannotBeCarried() {
        String error = encodeError(codec, message(QoS.NONE, new WithMap(Map.of("a", "b"))));
        assertTrue(error.contains("WithMap component 'map' has type java.util.Map<java.lang.String, java.lang.String>, "
                + "which the codec cannot carry"), error);
    }

    @Test
    void shouldRefuseCharactersXmlCannotCarryAndNameTheField() {
        assertTrue(encodeError(codec, message(QoS.NONE, new Text("a\u0000b")))
                .contains("contents type 'text': field 'text': character U+0000 at index 1 cannot be carried by XML 1.0"));
        assertTrue(encodeError(codec, message(QoS.NONE, new Text("\uFFFE"))).contains("character U+FFFE at index 0"));
        assertTrue(encodeError(codec, message(QoS.NONE, new Text("ok\uD800"))).contains("character U+D800 at index 2"));
        assertTrue(encodeError(codec, message(QoS.NONE, new Text("\uDC00ok"))).contains("character U+DC00 at index 0"));
        assertTrue(encodeError(codec, message(QoS.NONE, new Text("\u001B[0m"))).contains("character U+001B"));
    }

    @Test
    void shouldGiveThePathOfAValueDeepInsideTheRecord() {
        var generator = new MessageGenerator(1);
        Everything valid = generator.everything();
        var everything = new Everything(valid.flag(), valid.b(), valid.s(), valid.c(), valid.i(), valid.l(), valid.f(),
                valid.d(), null, null, null, null, null, "ok", valid.mode(), valid.target(), valid.ref(), valid.point(),
                valid.points(), Arrays.asList("fine", "bad\u0007"), valid.numbers(), valid.matrix(), valid.modes());
        String error = encodeError(codec, message(QoS.NONE, everything));
        assertTrue(error.contains("contents type 'everything': field 'names[1]': character U+0007 at index 3"), error);
    }

    @Test
    void shouldRefuseWhatTheDecoderWouldRejectWhenALimitIsExceeded() {
        MessageCodec small = MessageCodec.builder().contentsTypes(TestContents.registry())
                .maxDocumentBytes(2048).maxTextLength(1000).maxNestingDepth(8).build();
        assertTrue(encodeError(small, message(QoS.NONE, new Text("x".repeat(1001))))
                .contains("field 'text': text longer than maxTextLength=1000 (1001 chars)"));
        var samples = new MessageGenerator(2).samples(40);
        assertTrue(encodeError(small, message(QoS.NONE, samples)).contains("bytes, over maxDocumentBytes=2048"));
        assertTrue(encodeError(small, message(QoS.NONE, Node.chain(4))).contains("nests deeper than maxNestingDepth=8"));
        Message deepest = message(QoS.NONE, Node.chain(3));
        assertEquals(deepest, small.decode(small.encode(deepest)), "what the encoder accepts, the decoder accepts");
    }

    @Test
    void shouldRejectAMessageOfUnregisteredContentsWhenTheRegistryIsAnother() {
        Message angles = message(QoS.NONE, new TestContents.Angles(1, 2, 3, 4));
        byte[] document = codec.encode(angles);
        var plain = new MessageCodec(new ContentsTypes());
        var error = assertThrows(MessageFormatException.class, () -> plain.decode(document));
        assertTrue(error.getMessage().startsWith("unknown contents type 'angles'"), error.getMessage());
    }

    @Test
    void shouldUseTheGivenRegistryAndDocumentedLimitsByDefault() {
        var types = new ContentsTypes();
        var defaults = new MessageCodec(types);
        assertSame(types, defaults.contentsTypes());
        assertEquals(java.util.Set.of("empty", "text", "tick"), MessageCodec.builder().build().contentsTypes().names());
        assertEquals(1 << 20, defaults.maxDocumentBytes());
        assertEquals(MessageCodec.DEFAULT_MAX_NESTING_DEPTH, defaults.maxNestingDepth());
        assertEquals(MessageCodec.DEFAULT_MAX_TEXT_LENGTH, defaults.maxTextLength());
        Message tick = message(QoS.NONE, new Tick(1, 2, 3));
        assertEquals(tick, defaults.decode(defaults.encode(tick)));
        assertEquals(message(QoS.NONE, Empty.INSTANCE), defaults.decode(defaults.encode(message(QoS.NONE, Empty.INSTANCE))));
    }

    @Test
    void shouldNameTheSettingAndValueWhenALimitIsOutOfRange() {
        assertBuildError(MessageCodec.builder().maxDocumentBytes(10), "maxDocumentBytes=10 must be in [256, 268435456]");
        assertBuildError(MessageCodec.builder().maxDocumentBytes(Integer.MAX_VALUE), "maxDocumentBytes=2147483647");
        assertBuildError(MessageCodec.builder().maxNestingDepth(2), "maxNestingDepth=2 must be in [3, 1000]");
        assertBuildError(MessageCodec.builder().maxNestingDepth(5000), "maxNestingDepth=5000 must be in [3, 1000]");
        assertBuildError(MessageCodec.builder().maxTextLength(-1), "maxTextLength=-1 must be in [64, 268435456]");
        var nullRegistry = assertThrows(NullPointerException.class, () -> MessageCodec.builder().contentsTypes(null));
        assertEquals("contentsTypes", nullRegistry.getMessage());
    }

    @Test
    void shouldRefuseNullArguments() {
        assertThrows(NullPointerException.class, () -> codec.encode(null));
        assertThrows(NullPointerException.class, () -> codec.decode((byte[]) null));
        assertThrows(NullPointerException.class, () -> codec.decode((String) null));
    }

    private static void assertBuildError(MessageCodec.Builder builder, String expected) {
        var error = assertThrows(IllegalArgumentException.class, builder::build);
        assertTrue(error.getMessage().contains(expected), error.getMessage());
    }

    private static String encodeError(MessageCodec codec, Message message) {
        var error = assertThrows(MessageFormatException.class, () -> codec.encode(message));
        assertEquals(MessageFormatException.class, error.getClass());
        assertThrows(MessageFormatException.class, () -> codec.encodeToString(message));
        return error.getMessage();
    }
}
