package io.etherware.core.codec.internal;

import com.fasterxml.jackson.dataformat.xml.ser.ToXmlGenerator;
import io.etherware.core.codec.internal.ValueType.ArrayType;
import io.etherware.core.codec.internal.ValueType.ContentsType;
import io.etherware.core.codec.internal.ValueType.EnumType;
import io.etherware.core.codec.internal.ValueType.ListType;
import io.etherware.core.codec.internal.ValueType.RecordType;
import io.etherware.core.codec.internal.ValueType.Scalar;
import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.MessageFormatException;

import java.io.IOException;
import java.util.List;

/**
 * Streams a contents record into a {@link ToXmlGenerator}: components as child elements in
 * declaration order, nulls as {@code xsi:nil}, polymorphic fields with a {@code type} attribute.
 *
 * <p>It refuses what the decoder with the same limits would reject (text too long, nesting too
 * deep, characters XML 1.0 cannot carry), so a message that encodes also decodes. Stateless
 * apart from its configuration; thread-safe.
 */
final class ContentsWriter {

    private final ContentsTypes types;
    private final int maxNestingDepth;
    private final int maxTextLength;

    ContentsWriter(ContentsTypes types, int maxNestingDepth, int maxTextLength) {
        this.types = types;
        this.maxNestingDepth = maxNestingDepth;
        this.maxTextLength = maxTextLength;
    }

    /**
     * Writes a polymorphic element (the caller has written its name): the registered type name
     * as the {@code type} attribute, then the record's components.
     *
     * @param depth the element's depth in the document, the root being 1
     */
    void writeContents(ToXmlGenerator generator, Contents contents, int depth) throws IOException {
        String name;
        try {
            name = types.nameOf(contents.getClass());
        } catch (MessageFormatException e) {
            throw new FieldError(e.getMessage());
        }
        generator.writeStartObject();
        generator.setNextIsAttribute(true);
        generator.writeFieldName(Wire.TYPE);
        generator.writeString(name);
        generator.setNextIsAttribute(false);
        writeComponents(generator, RecordShape.of(contents.getClass()), contents, depth);
        generator.writeEndObject();
    }

    private void writeComponents(ToXmlGenerator generator, RecordShape shape, Object record, int depth) throws IOException {
        int childDepth = depth + 1;
        if (shape.size() > 0 && childDepth > maxNestingDepth) {
            throw new FieldError("nests deeper than maxNestingDepth=" + maxNestingDepth);
        }
        for (int i = 0; i < shape.size(); i++) {
            try {
                generator.writeFieldName(shape.names[i]);
                writeValue(generator, shape.types[i], shape.get(record, i), childDepth);
            } catch (FieldError e) {
                throw e.inField(shape.names[i]);
            }
        }
    }

    private void writeValue(ToXmlGenerator generator, ValueType type, Object value, int depth) throws IOException {
        if (value == null) {
            generator.writeNull(); // <name xsi:nil="true"/>: null, as opposed to an empty string or list
            return;
        }
        switch (type) {
            case Scalar scalar -> writeScalar(generator, scalar, value);
            case EnumType ignored -> generator.writeString(((Enum<?>) value).name());
            case ArrayType array -> writeText(generator, Scalars.formatArray(array.kind(), value));
            case RecordType ignored -> {
                generator.writeStartObject();
                writeComponents(generator, RecordShape.of(value.getClass()), value, depth);
                generator.writeEndObject();
            }
            case ContentsType ignored -> writeContents(generator, (Contents) value, depth);
            case ListType list -> writeList(generator, list, (List<?>) value, depth);
        }
    }

    private void writeScalar(ToXmlGenerator generator, Scalar scalar, Object value) throws IOException {
        switch (scalar.kind()) {
            case INT -> generator.writeNumber((Integer) value);
            case LONG -> generator.writeNumber((Long) value);
            case BOOLEAN -> generator.writeBoolean((Boolean) value);
            case STRING -> writeText(generator, (String) value);
            default -> writeText(generator, Scalars.format(scalar.kind(), value));
        }
    }

    private void writeList(ToXmlGenerator generator, ListType list, List<?> values, int depth) throws IOException {
        generator.writeStartObject();
        int itemDepth = depth + 1;
        if (!values.isEmpty() && itemDepth > maxNestingDepth) {
            throw new FieldError("nests deeper than maxNestingDepth=" + maxNestingDepth);
        }
        int index = 0;
        for (Object value : values) {
            try {
                generator.writeFieldName(Wire.ITEM);
                writeValue(generator, list.element(), value, itemDepth);
            } catch (FieldError e) {
                throw e.inItem(index);
            }
            index++;
        }
        generator.writeEndObject();
    }

    private void writeText(ToXmlGenerator generator, String text) throws IOException {
        checkText(text, maxTextLength);
        generator.writeString(text);
    }

    /** Refuses text the decoder would reject or that XML 1.0 cannot carry. */
    static void checkText(String text, int maxTextLength) {
        if (text.length() > maxTextLength) {
            throw new FieldError(ContentsReader.tooLong(text.length(), maxTextLength));
        }
        int invalid = Scalars.firstInvalidXmlChar(text);
        if (invalid >= 0) {
            throw new FieldError(String.format("character U+%04X at index %d cannot be carried by XML 1.0",
                    (int) text.charAt(invalid), invalid));
        }
    }
}
