package io.etherware.core.codec;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.etherware.core.message.Message;
import java.util.HashSet;
import java.util.Set;
import org.junit.jupiter.api.Test;
import org.xml.sax.SAXException;

/**
 * A seeded property test of the codec: thousands of generated messages, each encoded, decoded,
 * and its document checked against the XSD. Deterministic, but seconds of CPU on a loaded box,
 * so it runs with the integration tests; {@link MessageCodecRoundTripTest} has the chosen cases.
 */
class MessageCodecRoundTripIT {

    private static final int GENERATED_MESSAGES = 3_000;

    private final MessageCodec codec = MessageCodec.builder().contentsTypes(TestContents.registry()).build();

    @Test
    void shouldRoundTripExactlyWhenMessagesAreGeneratedAtRandom() throws SAXException {
        var generator = new MessageGenerator(MessageCodecRoundTripTest.SEED);
        Set<Class<?>> contentsSeen = new HashSet<>();
        for (int i = 0; i < GENERATED_MESSAGES; i++) {
            Message message = generator.message(i);
            byte[] document = codec.encode(message);
            Message decoded = codec.decode(document);
            assertEquals(message, decoded,
                    () -> "message " + message + " as " + MessageCodecRoundTripTest.utf8(document));
            assertEquals(message, codec.decode(codec.encodeToString(message)));
            Schemas.validate(document);
            contentsSeen.add(message.contents().getClass());
        }
        assertEquals(10, contentsSeen.size(), "every contents shape was generated: " + contentsSeen);
    }
}
