package io.etherware.core.codec.internal;

import io.etherware.core.codec.internal.ValueType.ArrayKind;
import io.etherware.core.codec.internal.ValueType.ScalarKind;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;

import java.util.Base64;
import java.util.regex.Pattern;

/**
 * Text forms of scalar values and primitive arrays, in both directions.
 *
 * <p>Numbers use the XML Schema lexical forms ({@code xs:long}, {@code xs:double}); floating
 * point is written in Java's shortest round-tripping form, with {@code INF}, {@code -INF} and
 * {@code NaN} for the special values, so every value reads back bit-exact (except NaN payloads).
 * Whitespace around numbers, booleans and enum names is ignored on input, as XML Schema does;
 * strings are taken exactly. Stateless and thread-safe.
 */
final class Scalars {

    private static final Pattern XML_SPACES = Pattern.compile("[ \t\r\n]+");

    private Scalars() {
    }

    /** The text of a non-null scalar. Characters are checked later, by the caller that writes them. */
    static String format(ScalarKind kind, Object value) {
        return switch (kind) {
            case FLOAT -> formatFloat((Float) value);
            case DOUBLE -> formatDouble((Double) value);
            case CHAR -> String.valueOf((char) (Character) value);
            default -> value.toString();
        };
    }

    static String formatDouble(double value) {
        if (Double.isInfinite(value)) {
            return value > 0 ? "INF" : "-INF";
        }
        return Double.toString(value);
    }

    static String formatFloat(float value) {
        if (Float.isInfinite(value)) {
            return value > 0 ? "INF" : "-INF";
        }
        return Float.toString(value);
    }

    /**
     * Parses the text of a scalar.
     *
     * @throws FieldError naming the text and the expected type
     */
    static Object parse(ScalarKind kind, String text) {
        if (kind == ScalarKind.STRING || kind == ScalarKind.CHAR) {
            // Woodstox lets U+FFFE, U+FFFF and unpaired surrogates through; the encoder could not write them back.
            int invalid = firstInvalidXmlChar(text);
            if (invalid >= 0) {
                throw new FieldError(String.format("character U+%04X at index %d is not allowed in XML 1.0",
                        (int) text.charAt(invalid), invalid));
            }
        }
        try {
            return switch (kind) {
                case STRING -> text;
                case BOOLEAN -> parseBoolean(strip(text));
                case BYTE -> Byte.parseByte(strip(text));
                case SHORT -> Short.parseShort(strip(text));
                case INT -> Integer.parseInt(strip(text));
                case LONG -> Long.parseLong(strip(text));
                case FLOAT -> parseFloat(strip(text));
                case DOUBLE -> parseDouble(strip(text));
                case CHAR -> parseChar(text);
                case PROFILE -> Profile.parse(text);
                case MESSAGE_ID -> MessageId.parse(text);
            };
        } catch (NumberFormatException e) {
            throw new FieldError(quote(text) + " is not " + article(kind.javaName) + " " + kind.javaName);
        } catch (IllegalArgumentException e) {
            throw new FieldError(e.getMessage());
        }
    }

    static long parseLong(String text) {
        try {
            return Long.parseLong(strip(text));
        } catch (NumberFormatException e) {
            throw new FieldError(quote(text) + " is not a long");
        }
    }

    private static Boolean parseBoolean(String text) {
        return switch (text) {
            case "true", "1" -> Boolean.TRUE;
            case "false", "0" -> Boolean.FALSE;
            default -> throw new NumberFormatException(text);
        };
    }

    private static Character parseChar(String text) {
        if (text.length() != 1) {
            throw new NumberFormatException(text);
        }
        return text.charAt(0);
    }

    static double parseDouble(String text) {
        return switch (text) {
            case "INF" -> Double.POSITIVE_INFINITY;
            case "-INF" -> Double.NEGATIVE_INFINITY;
            default -> Double.parseDouble(requireDecimal(text));
        };
    }

    private static float parseFloat(String text) {
        return switch (text) {
            case "INF" -> Float.POSITIVE_INFINITY;
            case "-INF" -> Float.NEGATIVE_INFINITY;
            default -> Float.parseFloat(requireDecimal(text));
        };
    }

    /** Java also accepts hex floats and 'd'/'f' suffixes; the wire format does not. */
    private static String requireDecimal(String text) {
        if (text.isEmpty() || "NaN".equals(text) || "Infinity".equals(text) || "-Infinity".equals(text)) {
            return text;
        }
        char last = text.charAt(text.length() - 1);
        if (!(last >= '0' && last <= '9' || last == '.') || text.indexOf('x') >= 0 || text.indexOf('X') >= 0) {
            throw new NumberFormatException(text);
        }
        return text;
    }

    /** The text of a non-null primitive array. */
    static String formatArray(ArrayKind kind, Object array) {
        if (kind == ArrayKind.BYTE) {
            return Base64.getEncoder().encodeToString((byte[]) array);
        }
        var text = new StringBuilder();
        switch (kind) {
            case INT -> {
                for (int value : (int[]) array) {
                    separate(text).append(value);
                }
            }
            case LONG -> {
                for (long value : (long[]) array) {
                    separate(text).append(value);
                }
            }
            case DOUBLE -> {
                for (double value : (double[]) array) {
                    separate(text).append(formatDouble(value));
                }
            }
            default -> throw new IllegalStateException(kind.name());
        }
        return text.toString();
    }

    private static StringBuilder separate(StringBuilder text) {
        return text.isEmpty() ? text : text.append(' ');
    }

    /** Parses whitespace-separated numbers (or base64 for bytes). */
    static Object parseArray(ArrayKind kind, String text) {
        if (kind == ArrayKind.BYTE) {
            try {
                return Base64.getDecoder().decode(XML_SPACES.matcher(text).replaceAll(""));
            } catch (IllegalArgumentException e) {
                throw new FieldError("is not base64: " + e.getMessage());
            }
        }
        String[] tokens = tokens(text);
        int index = 0;
        try {
            switch (kind) {
                case INT -> {
                    int[] values = new int[tokens.length];
                    for (; index < tokens.length; index++) {
                        values[index] = Integer.parseInt(tokens[index]);
                    }
                    return values;
                }
                case LONG -> {
                    long[] values = new long[tokens.length];
                    for (; index < tokens.length; index++) {
                        values[index] = Long.parseLong(tokens[index]);
                    }
                    return values;
                }
                case DOUBLE -> {
                    double[] values = new double[tokens.length];
                    for (; index < tokens.length; index++) {
                        values[index] = parseDouble(tokens[index]);
                    }
                    return values;
                }
                default -> throw new IllegalStateException(kind.name());
            }
        } catch (NumberFormatException e) {
            String element = kind.javaName.substring(0, kind.javaName.length() - 2);
            throw new FieldError("entry " + index + " " + quote(tokens[index]) + " is not " + article(element) + " " + element);
        }
    }

    private static String[] tokens(String text) {
        String stripped = strip(text);
        if (stripped.isEmpty()) {
            return new String[0];
        }
        return XML_SPACES.split(stripped);
    }

    /** Removes leading and trailing XML whitespace (space, tab, CR, LF) only. */
    static String strip(String text) {
        int start = 0;
        int end = text.length();
        while (start < end && isXmlSpace(text.charAt(start))) {
            start++;
        }
        while (end > start && isXmlSpace(text.charAt(end - 1))) {
            end--;
        }
        return start == 0 && end == text.length() ? text : text.substring(start, end);
    }

    static boolean isBlank(String text) {
        for (int i = 0; i < text.length(); i++) {
            if (!isXmlSpace(text.charAt(i))) {
                return false;
            }
        }
        return true;
    }

    private static boolean isXmlSpace(char c) {
        return c == ' ' || c == '\t' || c == '\n' || c == '\r';
    }

    /**
     * The index of the first character XML 1.0 cannot carry (controls other than tab, LF and
     * CR, U+FFFE, U+FFFF, unpaired surrogates), or -1.
     */
    static int firstInvalidXmlChar(String text) {
        for (int i = 0, n = text.length(); i < n; i++) {
            char c = text.charAt(i);
            if (c >= 0x20 && c < 0xD800) {
                continue;
            }
            if (c < 0x20) {
                if (c != '\t' && c != '\n' && c != '\r') {
                    return i;
                }
            } else if (Character.isHighSurrogate(c)) {
                if (i + 1 < n && Character.isLowSurrogate(text.charAt(i + 1))) {
                    i++;
                } else {
                    return i;
                }
            } else if (Character.isLowSurrogate(c) || c == 0xFFFE || c == 0xFFFF) {
                return i;
            }
        }
        return -1;
    }

    /** The text for an error message: quoted, and cut if long. */
    static String quote(String text) {
        return text.length() <= 40 ? "'" + text + "'" : "'" + text.substring(0, 37) + "...' (" + text.length() + " chars)";
    }

    private static String article(String word) {
        return "aeiouAEIOU".indexOf(word.charAt(0)) >= 0 ? "an" : "a";
    }
}
