package io.etherware.core.codec;

import io.etherware.core.message.Message;
import io.etherware.core.message.MessageFormatException;
import org.junit.jupiter.api.Test;

import java.nio.charset.StandardCharsets;
import java.util.Arrays;
import java.util.Random;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

/**
 * Seeded mutations of valid documents: whatever the damage, decoding either fails with a
 * {@link MessageFormatException} or yields a message that itself round-trips exactly.
 */
class MessageCodecFuzzTest {

    private static final long SEED = 0xF022L;
    private static final int MUTATIONS = 5_000;
    private static final byte[] INTERESTING = "<>&;/\"'=#[]! \r\n\t0-9aZ\u00e9".getBytes(StandardCharsets.UTF_8);

    private final MessageCodec codec = MessageCodec.builder().contentsTypes(TestContents.registry()).build();

    @Test
    void shouldEitherRejectCleanlyOrDecodeSomethingValidWhenDocumentsAreDamaged() {
        var random = new Random(SEED);
        var generator = new MessageGenerator(SEED);
        int rejected = 0;
        int decoded = 0;
        for (int i = 0; i < MUTATIONS; i++) {
            byte[] original = codec.encode(generator.message(i));
            byte[] damaged = mutate(original, random);
            Message message;
            try {
                message = codec.decode(damaged);
            } catch (MessageFormatException expected) {
                assertTrue(expected.getMessage() != null && !expected.getMessage().isBlank());
                rejected++;
                continue;
            } catch (RuntimeException | StackOverflowError e) {
                throw new AssertionError("raw " + e + " for " + new String(damaged, StandardCharsets.UTF_8), e);
            }
            decoded++;
            try {
                assertEquals(message, codec.decode(codec.encode(message)));
            } catch (MessageFormatException e) {
                fail("decoded message does not re-encode: " + e.getMessage());
            }
        }
        assertTrue(rejected > MUTATIONS / 4, "most damage is detected: " + rejected);
        assertTrue(decoded > 0, "some damage is harmless (inside text): " + decoded);
    }

    private static byte[] mutate(byte[] document, Random random) {
        byte[] result = document;
        for (int edits = 1 + random.nextInt(3); edits > 0; edits--) {
            int at = random.nextInt(result.length);
            result = switch (random.nextInt(5)) {
                case 0 -> { // replace a byte
                    byte[] copy = result.clone();
                    copy[at] = random.nextBoolean() ? INTERESTING[random.nextInt(INTERESTING.length)] : (byte) random.nextInt();
                    yield copy;
                }
                case 1 -> { // delete a byte
                    byte[] copy = new byte[result.length - 1];
                    System.arraycopy(result, 0, copy, 0, at);
                    System.arraycopy(result, at + 1, copy, at, result.length - at - 1);
                    yield copy;
                }
                case 2 -> { // insert a byte
                    byte[] copy = new byte[result.length + 1];
                    System.arraycopy(result, 0, copy, 0, at);
                    copy[at] = INTERESTING[random.nextInt(INTERESTING.length)];
                    System.arraycopy(result, at, copy, at + 1, result.length - at);
                    yield copy;
                }
                case 3 -> Arrays.copyOf(result, at); // truncate
                default -> { // duplicate a slice
                    int length = Math.min(result.length - at, 1 + random.nextInt(40));
                    byte[] copy = new byte[result.length + length];
                    System.arraycopy(result, 0, copy, 0, at + length);
                    System.arraycopy(result, at, copy, at + length, result.length - at);
                    yield copy;
                }
            };
            if (result.length == 0) {
                break;
            }
        }
        return result;
    }
}
