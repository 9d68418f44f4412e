package io.etherware.core.codec;

import com.code_intelligence.jazzer.junit.DictionaryEntries;
import com.code_intelligence.jazzer.junit.FuzzTest;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageFormatException;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

import java.nio.charset.StandardCharsets;
import java.util.Arrays;
import java.util.ConcurrentModificationException;
import java.util.NoSuchElementException;
import java.util.Random;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

/**
 * Whatever the bytes, decoding either fails with a {@link MessageFormatException} that is not a
 * bug in disguise, or yields a message that itself round-trips exactly.
 *
 * <p>Two drivers: seeded random mutations of valid documents (a plain test, not coverage-guided),
 * and a Jazzer {@link FuzzTest}. In a normal build Jazzer only replays the seed corpus in
 * {@code src/test/resources/io/etherware/core/codec/MessageCodecFuzzITInputs/}; to fuzz, see
 * "Fuzzing" in the README.
 */
class MessageCodecFuzzIT {

    private static final long SEED = 0xF022L;
    private static final int MUTATIONS = 5_000;
    private static final byte[] INTERESTING = "<>&;/\"'=#[]! \r\n\t0-9aZ\u00e9".getBytes(StandardCharsets.UTF_8);

    /** Fuzz inputs beyond this are skipped; the codec's limit below rejects most of them. */
    private static final int MAX_INPUT_BYTES = 64 * 1024;
    private static final int MAX_DOCUMENT_BYTES = 16 * 1024;
    /** The codec under fuzzing: a document limit well under the input bound, so that path runs too. */
    private static final MessageCodec LIMITED = MessageCodec.builder().contentsTypes(TestContents.registry())
            .maxDocumentBytes(MAX_DOCUMENT_BYTES).build();
    /**
     * Re-encodes decoded messages: same nesting and text limits, more room for the document, as a
     * re-encoding may be longer than a compact input (1e3 comes back as 1000.0).
     */
    private static final MessageCodec ROOMY = MessageCodec.builder().contentsTypes(TestContents.registry())
            .maxDocumentBytes(16 * MAX_DOCUMENT_BYTES).build();

    private final MessageCodec codec = MessageCodec.builder().contentsTypes(TestContents.registry()).build();

    @DictionaryEntries({"<message version=\"1\">", "</message>", "<profile>", "</profile>", "<sender>",
            "<timeStamp>", "<qos>", "<criticality>", "<periodNs>", "<deadlineNs>", "<wcetNs>", "<messageId>",
            "<correlationId>", "<contents type=\"", "</contents>", "<item type=\"", "<item>", "</item>",
            "xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" xsi:nil=\"true\"", "<![CDATA[", "]]>",
            "&#x", "&lt;", "<!DOCTYPE", "<?xml version=\"1.0\" encoding=\"", "tick", "holder", "samples",
            "everything", "counter-state", "text", "empty", "NaN", "-INF", "-0.0", "1.0E-300",
            "9223372036854775807", "[car=1]", "node1#"})
    @Timeout(10)
    @FuzzTest(maxDuration = "30s")
    void shouldRejectCleanlyOrRoundTripAnyBytes(byte[] document) {
        if (document.length > MAX_INPUT_BYTES) {
            return;
        }
        Message message;
        try {
            message = LIMITED.decode(document);
        } catch (MessageFormatException rejected) {
            requireCleanRejection(rejected, document);
            return;
        }
        byte[] encoded;
        try {
            encoded = ROOMY.encode(message);
        } catch (MessageFormatException e) {
            throw new AssertionError("decoded " + message + " from " + show(document) + " but cannot encode it", e);
        }
        Message again;
        try {
            again = ROOMY.decode(encoded);
        } catch (MessageFormatException e) {
            throw new AssertionError("re-encoded " + show(encoded) + " does not decode (from " + show(document) + ")", e);
        }
        assertEquals(message, again, () -> "round trip of " + show(document) + " via " + show(encoded));
    }

    /**
     * A rejection must say why, and must not be a programming error the codec wrapped as a format
     * error (its catch-all turns any exception into a {@link MessageFormatException}).
     */
    private static void requireCleanRejection(MessageFormatException rejected, byte[] document) {
        String reason = rejected.getMessage();
        if (reason == null || reason.isBlank()) {
            throw new AssertionError("rejected without a reason: " + show(document), rejected);
        }
        for (Throwable cause = rejected.getCause(); cause != null; cause = cause.getCause() == cause ? null : cause.getCause()) {
            if (isProgrammingError(cause)) {
                throw new AssertionError("a bug reported as a format error (" + reason + ") for " + show(document),
                        rejected);
            }
        }
        // The codec's last-resort translation of an exception it did not expect.
        if (reason.startsWith("cannot decode message: ") && rejected.getCause() instanceof RuntimeException raw) {
            throw new AssertionError("unexpected " + raw + " for " + show(document), rejected);
        }
    }

    private static boolean isProgrammingError(Throwable t) {
        return t instanceof NullPointerException || t instanceof ClassCastException
                || t instanceof IndexOutOfBoundsException || t instanceof ArithmeticException
                || t instanceof IllegalStateException || t instanceof UnsupportedOperationException
                || t instanceof NegativeArraySizeException || t instanceof ArrayStoreException
                || t instanceof NoSuchElementException || t instanceof ConcurrentModificationException
                || t instanceof Error;
    }

    private static String show(byte[] bytes) {
        String text = new String(bytes, StandardCharsets.UTF_8);
        return text.length() <= 2000 ? "'" + text + "'" : "'" + text.substring(0, 2000) + "'... (" + bytes.length + " bytes)";
    }

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
