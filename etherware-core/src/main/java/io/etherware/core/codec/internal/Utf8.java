package io.etherware.core.codec.internal;

import io.etherware.core.message.MessageFormatException;

/**
 * Strict UTF-8 validation (RFC 3629): no overlong forms, no surrogates, nothing above U+10FFFF,
 * no truncated sequences. Woodstox's decoder accepts overlong two-byte forms (C0 AF for '/'),
 * which a filter in front of the parser would not see as markup; so every byte is checked here
 * first. Stateless; thread-safe.
 */
final class Utf8 {

    private Utf8() {
    }

    /**
     * Checks {@code bytes} is well-formed UTF-8.
     *
     * @throws MessageFormatException naming the offset and the offending byte
     */
    static void requireValid(byte[] bytes) {
        int i = 0;
        int n = bytes.length;
        while (i < n) {
            int b = bytes[i];
            if (b >= 0) {
                i++;
                continue;
            }
            b &= 0xFF;
            int length;
            int secondMin = 0x80;
            int secondMax = 0xBF;
            if (b >= 0xC2 && b <= 0xDF) {
                length = 2;
            } else if (b >= 0xE0 && b <= 0xEF) {
                length = 3;
                if (b == 0xE0) {
                    secondMin = 0xA0; // shorter forms are overlong
                } else if (b == 0xED) {
                    secondMax = 0x9F; // D800-DFFF are surrogates
                }
            } else if (b >= 0xF0 && b <= 0xF4) {
                length = 4;
                if (b == 0xF0) {
                    secondMin = 0x90;
                } else if (b == 0xF4) {
                    secondMax = 0x8F; // above U+10FFFF
                }
            } else {
                throw invalid(i, b, b == 0xC0 || b == 0xC1 ? "overlong encoding" : "invalid start byte");
            }
            if (i + length > n) {
                throw invalid(i, b, "sequence truncated by the end of the document");
            }
            int second = bytes[i + 1] & 0xFF;
            if (second < secondMin || second > secondMax) {
                throw invalid(i + 1, second, second >= 0x80 && second <= 0xBF
                        ? "makes an overlong encoding, a surrogate or a code point above U+10FFFF"
                        : "invalid continuation byte");
            }
            for (int k = 2; k < length; k++) {
                int next = bytes[i + k] & 0xFF;
                if (next < 0x80 || next > 0xBF) {
                    throw invalid(i + k, next, "invalid continuation byte");
                }
            }
            i += length;
        }
    }

    private static MessageFormatException invalid(int offset, int value, String what) {
        return new MessageFormatException(String.format("not valid UTF-8 (messages are UTF-8): byte 0x%02X at offset %d: %s",
                value, offset, what));
    }
}
