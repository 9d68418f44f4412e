package io.etherware.core.codec.internal;

import com.fasterxml.jackson.core.JsonParser;
import com.fasterxml.jackson.core.JsonToken;
import com.fasterxml.jackson.databind.DeserializationContext;
import com.fasterxml.jackson.databind.deser.std.StdDeserializer;
import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageFormatException;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;

import java.io.IOException;

/**
 * Reads the {@code <message>} envelope from Jackson's XML token stream, streaming (no tree).
 *
 * <p>Children may come in any order but each at most once; unknown elements, missing required
 * ones and values that do not fit their record are {@link MessageFormatException}s naming the
 * element. Stateless apart from its registry; thread-safe.
 */
public final class EnvelopeDeserializer extends StdDeserializer<Message> {

    private final ContentsReader contentsReader;
    private final ProfileCache profiles = new ProfileCache();
    private final int maxTextLength;

    public EnvelopeDeserializer(ContentsTypes types, int maxTextLength) {
        super(Message.class);
        this.contentsReader = new ContentsReader(types, maxTextLength);
        this.maxTextLength = maxTextLength;
    }

    @Override
    public Message deserialize(JsonParser parser, DeserializationContext context) throws IOException {
        Profile profile = null;
        Profile sender = null;
        long timeStamp = 0;
        boolean hasTimeStamp = false;
        QoS qos = null;
        MessageId messageId = null;
        MessageId correlationId = null;
        Contents contents = null;

        if (parser.currentToken() == JsonToken.START_OBJECT) {
            for (JsonToken token = parser.nextToken(); token != JsonToken.END_OBJECT; token = parser.nextToken()) {
                if (token != JsonToken.FIELD_NAME) {
                    throw new MessageFormatException("unexpected " + token + " in <message>");
                }
                String name = parser.currentName();
                switch (name) {
                    case Wire.VERSION -> {
                        String version = Scalars.strip(text(parser, name));
                        if (!Wire.VERSION_1.equals(version)) {
                            throw new MessageFormatException("unsupported wire format version '" + version
                                    + "'; this codec reads version " + Wire.VERSION_1);
                        }
                    }
                    case Wire.PROFILE -> profile = profile(parser, name, profile);
                    case Wire.SENDER -> sender = profile(parser, name, sender);
                    case Wire.TIME_STAMP -> {
                        once(name, hasTimeStamp);
                        timeStamp = parseLong(name, text(parser, name));
                        hasTimeStamp = true;
                    }
                    case Wire.QOS -> {
                        once(name, qos != null);
                        parser.nextToken();
                        qos = readQos(parser);
                    }
                    case Wire.MESSAGE_ID -> messageId = messageId(parser, name, messageId);
                    case Wire.CORRELATION_ID -> correlationId = messageId(parser, name, correlationId);
                    case Wire.CONTENTS -> {
                        once(name, contents != null);
                        parser.nextToken();
                        contents = contentsReader.readContents(parser);
                    }
                    case "" -> requireBlank(parser, "<message>");
                    default -> throw new MessageFormatException("unexpected element <" + name + "> in <message>");
                }
            }
        } else if (parser.currentToken() != JsonToken.VALUE_STRING || !Scalars.isBlank(parser.getText())) {
            throw new MessageFormatException("<message> must contain elements, found " + parser.currentToken());
        }
        require(Wire.PROFILE, profile != null);
        require(Wire.TIME_STAMP, hasTimeStamp);
        require(Wire.QOS, qos != null);
        require(Wire.MESSAGE_ID, messageId != null);
        require(Wire.CONTENTS, contents != null);
        return new Message(profile, sender, timeStamp, qos, contents, messageId, correlationId);
    }

    private QoS readQos(JsonParser parser) throws IOException {
        Criticality criticality = null;
        long periodNs = 0;
        long deadlineNs = 0;
        long wcetNs = 0;
        int seen = 0;
        if (parser.currentToken() == JsonToken.START_OBJECT) {
            for (JsonToken token = parser.nextToken(); token != JsonToken.END_OBJECT; token = parser.nextToken()) {
                if (token != JsonToken.FIELD_NAME) {
                    throw new MessageFormatException("unexpected " + token + " in <qos>");
                }
                String name = parser.currentName();
                int bit = switch (name) {
                    case Wire.CRITICALITY -> 1;
                    case Wire.PERIOD_NS -> 2;
                    case Wire.DEADLINE_NS -> 4;
                    case Wire.WCET_NS -> 8;
                    case "" -> 0;
                    default -> throw new MessageFormatException("unexpected element <" + name + "> in <qos>");
                };
                if (bit == 0) {
                    requireBlank(parser, "<qos>");
                    continue;
                }
                if ((seen & bit) != 0) {
                    throw new MessageFormatException("<" + name + "> appears twice in <qos>");
                }
                seen |= bit;
                String text = text(parser, name);
                switch (name) {
                    case Wire.CRITICALITY -> criticality = criticality(text);
                    case Wire.PERIOD_NS -> periodNs = presentDuration(name, text);
                    case Wire.DEADLINE_NS -> deadlineNs = presentDuration(name, text);
                    default -> wcetNs = presentDuration(name, text);
                }
            }
        }
        if (criticality == null) {
            throw new MessageFormatException("<qos> has no <criticality>");
        }
        if (criticality == Criticality.NONE && periodNs == 0 && deadlineNs == 0 && wcetNs == 0) {
            return QoS.NONE;
        }
        try {
            return new QoS(criticality, periodNs, deadlineNs, wcetNs);
        } catch (IllegalArgumentException e) {
            throw new MessageFormatException("malformed <qos>: " + e.getMessage(), e);
        }
    }

    /**
     * A duration that is present on the wire: 0 means "not specified" in {@link QoS} and the
     * encoder omits it, so an explicit 0 is a peer's mistake (a deadline of 0 would be missed by
     * every job), not a way to say "none".
     */
    private static long presentDuration(String name, String text) {
        long valueNs = parseLong(name, text);
        if (valueNs == 0) {
            throw new MessageFormatException("<" + name + "> is 0: a duration that is present must be > 0;"
                    + " omit the element when there is none");
        }
        return valueNs;
    }

    private static Criticality criticality(String text) {
        return switch (Scalars.strip(text)) {
            case "NONE" -> Criticality.NONE;
            case "LOW" -> Criticality.LOW;
            case "MIDDLE" -> Criticality.MIDDLE;
            case "HIGH" -> Criticality.HIGH;
            default -> throw new MessageFormatException("malformed <qos>: criticality " + Scalars.quote(text)
                    + " is not one of NONE, LOW, MIDDLE, HIGH");
        };
    }

    private Profile profile(JsonParser parser, String name, Profile previous) throws IOException {
        once(name, previous != null);
        String text = text(parser, name);
        try {
            return profiles.parse(text);
        } catch (IllegalArgumentException e) {
            throw new MessageFormatException("malformed <" + name + ">: " + e.getMessage(), e);
        }
    }

    private MessageId messageId(JsonParser parser, String name, MessageId previous) throws IOException {
        once(name, previous != null);
        String text = text(parser, name);
        try {
            return MessageId.parse(text);
        } catch (IllegalArgumentException e) {
            throw new MessageFormatException("malformed <" + name + ">: " + e.getMessage(), e);
        }
    }

    private static long parseLong(String name, String text) {
        try {
            return Scalars.parseLong(text);
        } catch (FieldError e) {
            throw new MessageFormatException("malformed <" + name + ">: " + e.getMessage());
        }
    }

    /** Moves to the value of element {@code name} and returns its text. */
    private String text(JsonParser parser, String name) throws IOException {
        JsonToken token = parser.nextToken();
        if (token == JsonToken.VALUE_NULL) {
            throw new MessageFormatException("<" + name + "> must not be nil");
        }
        if (token == null || !token.isScalarValue()) {
            throw new MessageFormatException("<" + name + "> must be text, found child elements or attributes");
        }
        String text = parser.getText();
        if (text.length() > maxTextLength) {
            throw new MessageFormatException("<" + name + ">: " + ContentsReader.tooLong(text.length(), maxTextLength));
        }
        return text;
    }

    private static void requireBlank(JsonParser parser, String where) throws IOException {
        parser.nextToken();
        String text = parser.getText();
        if (text != null && !Scalars.isBlank(text)) {
            throw new MessageFormatException("unexpected text " + Scalars.quote(text) + " in " + where);
        }
    }

    private static void once(String name, boolean alreadySeen) {
        if (alreadySeen) {
            throw new MessageFormatException("<" + name + "> appears twice in <message>");
        }
    }

    private static void require(String name, boolean present) {
        if (!present) {
            throw new MessageFormatException("<message> has no <" + name + ">");
        }
    }
}
