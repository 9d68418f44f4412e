package io.etherware.core.codec.internal;

import com.fasterxml.jackson.core.JsonGenerator;
import com.fasterxml.jackson.databind.SerializerProvider;
import com.fasterxml.jackson.databind.ser.std.StdSerializer;
import com.fasterxml.jackson.dataformat.xml.ser.ToXmlGenerator;
import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageFormatException;
import io.etherware.core.message.QoS;

import java.io.IOException;

/**
 * Writes a {@link Message} as the {@code <message>} envelope, streaming straight into Jackson's
 * XML generator (no intermediate tree). The root element's name comes from the ObjectWriter.
 *
 * <p>QoS durations of 0 ("not specified") are omitted; {@code sender} and {@code correlationId}
 * are omitted when null. Stateless apart from its configuration; thread-safe.
 */
public final class EnvelopeSerializer extends StdSerializer<Message> {

    private final ContentsTypes types;
    private final ContentsWriter contentsWriter;
    private final int maxTextLength;

    public EnvelopeSerializer(ContentsTypes types, int maxNestingDepth, int maxTextLength) {
        super(Message.class);
        this.types = types;
        this.contentsWriter = new ContentsWriter(types, maxNestingDepth, maxTextLength);
        this.maxTextLength = maxTextLength;
    }

    @Override
    public void serialize(Message message, JsonGenerator generator, SerializerProvider provider) throws IOException {
        ToXmlGenerator xml = (ToXmlGenerator) generator;
        xml.writeStartObject();
        xml.setNextIsAttribute(true);
        xml.writeFieldName(Wire.VERSION);
        xml.writeString(Wire.VERSION_1);
        xml.setNextIsAttribute(false);

        writeText(xml, Wire.PROFILE, message.profile().toString());
        if (message.sender() != null) {
            writeText(xml, Wire.SENDER, message.sender().toString());
        }
        xml.writeFieldName(Wire.TIME_STAMP);
        xml.writeNumber(message.timeStamp());
        writeQos(xml, message.qos());
        writeText(xml, Wire.MESSAGE_ID, message.messageId().toString());
        if (message.correlationId() != null) {
            writeText(xml, Wire.CORRELATION_ID, message.correlationId().toString());
        }

        xml.writeFieldName(Wire.CONTENTS);
        try {
            contentsWriter.writeContents(xml, message.contents(), 2);
        } catch (FieldError e) {
            throw new MessageFormatException(label(message.contents()) + e.describe(), e.getCause());
        }
        xml.writeEndObject();
    }

    private static void writeQos(ToXmlGenerator xml, QoS qos) throws IOException {
        xml.writeFieldName(Wire.QOS);
        xml.writeStartObject();
        xml.writeFieldName(Wire.CRITICALITY);
        xml.writeString(qos.criticality().name());
        writeDuration(xml, Wire.PERIOD_NS, qos.periodNs());
        writeDuration(xml, Wire.DEADLINE_NS, qos.deadlineNs());
        writeDuration(xml, Wire.WCET_NS, qos.wcetNs());
        xml.writeEndObject();
    }

    private static void writeDuration(ToXmlGenerator xml, String name, long valueNs) throws IOException {
        if (valueNs != 0) {
            xml.writeFieldName(name);
            xml.writeNumber(valueNs);
        }
    }

    private void writeText(ToXmlGenerator xml, String name, String text) throws IOException {
        // Profiles and ids are restricted to safe characters by their records; only the length can be wrong.
        if (text.length() > maxTextLength) {
            throw new MessageFormatException("<" + name + ">: " + ContentsReader.tooLong(text.length(), maxTextLength));
        }
        xml.writeFieldName(name);
        xml.writeString(text);
    }

    private String label(Contents contents) {
        return types.isRegistered(contents.getClass())
                ? "contents type '" + types.nameOf(contents.getClass()) + "': "
                : "";
    }
}
