package io.etherware.core.codec.internal;

import io.etherware.core.message.MessageFormatException;

import javax.xml.stream.Location;
import javax.xml.stream.XMLStreamException;
import java.io.CharConversionException;
import java.util.regex.Pattern;

/**
 * Turns whatever Jackson or Woodstox threw into a {@link MessageFormatException} that says, in
 * our terms, what was wrong (and where, when the parser knows), keeping the original as cause.
 * Nothing from those libraries escapes the codec raw. Stateless; thread-safe.
 */
public final class CodecErrors {

    /** Woodstox appends "\n at [row,col {unknown-source}]: [1,14]"; we say it in words instead. */
    private static final Pattern WOODSTOX_LOCATION = Pattern.compile("\\s*at \\[row,col[^]]*]: \\[\\d+,\\d+]");

    private final int maxNestingDepth;
    private final int maxTextLength;

    public CodecErrors(int maxNestingDepth, int maxTextLength) {
        this.maxNestingDepth = maxNestingDepth;
        this.maxTextLength = maxTextLength;
    }

    /** The error to report for a failed decode. */
    public MessageFormatException decodeFailure(Throwable failure) {
        MessageFormatException ours = find(failure, MessageFormatException.class);
        if (ours != null) {
            return ours;
        }
        if (messageContains(failure, "Invalid UTF-8 character")) {
            // The bytes passed our strict UTF-8 check, so this is U+FFFE or U+FFFF, which XML forbids.
            return new MessageFormatException("character not allowed in XML 1.0: " + describe(deepest(failure)), failure);
        }
        if (find(failure, CharConversionException.class) != null || messageContains(failure, "Invalid UTF-8")) {
            return new MessageFormatException("not valid UTF-8: " + describe(deepest(failure)), failure);
        }
        XMLStreamException xml = find(failure, XMLStreamException.class);
        if (xml != null) {
            String text = describe(xml);
            if (text.contains("Element Depth limit")) {
                return new MessageFormatException("XML nested deeper than maxNestingDepth=" + maxNestingDepth + " (" + text
                        + ")", failure);
            }
            if (text.contains("size limit")) {
                return new MessageFormatException("text or attribute longer than maxTextLength=" + maxTextLength + " ("
                        + text + ")", failure);
            }
            if (text.contains("Unexpected EOF") || text.contains("Unexpected end of input")) {
                return new MessageFormatException("truncated or empty document: " + text, failure);
            }
            return new MessageFormatException("malformed XML: " + text, failure);
        }
        return new MessageFormatException("cannot decode message: " + describe(deepest(failure)), failure);
    }

    /** The error to report for a failed encode of the message with id {@code messageId}. */
    public MessageFormatException encodeFailure(Object messageId, Throwable failure) {
        MessageFormatException ours = find(failure, MessageFormatException.class);
        String reason = ours != null ? ours.getMessage() : describe(deepest(failure));
        return new MessageFormatException("cannot encode message " + messageId + ": " + reason, failure);
    }

    private static String describe(Throwable failure) {
        String message = failure.getMessage();
        if (message == null) {
            return failure.getClass().getSimpleName();
        }
        String text = WOODSTOX_LOCATION.matcher(message).replaceAll("").strip();
        if (failure instanceof XMLStreamException xml && xml.getLocation() != null) {
            Location location = xml.getLocation();
            if (location.getLineNumber() > 0) {
                text = (text.endsWith(".") ? text.substring(0, text.length() - 1) : text) + " at line " + location.getLineNumber() + ", column " + location.getColumnNumber();
            }
        }
        return text;
    }

    private static <T extends Throwable> T find(Throwable failure, Class<T> type) {
        for (Throwable t = failure; t != null; t = t.getCause() == t ? null : t.getCause()) {
            if (type.isInstance(t)) {
                return type.cast(t);
            }
        }
        return null;
    }

    private static boolean messageContains(Throwable failure, String text) {
        for (Throwable t = failure; t != null; t = t.getCause() == t ? null : t.getCause()) {
            if (t.getMessage() != null && t.getMessage().contains(text)) {
                return true;
            }
        }
        return false;
    }

    private static Throwable deepest(Throwable failure) {
        Throwable t = failure;
        while (t.getCause() != null && t.getCause() != t) {
            t = t.getCause();
        }
        return t;
    }
}
