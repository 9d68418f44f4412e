package io.etherware.core.codec.internal;

import com.fasterxml.jackson.core.JsonParser;
import com.fasterxml.jackson.core.JsonToken;
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
import java.util.ArrayList;
import java.util.Collections;
import java.util.List;

/**
 * Reads a contents record from Jackson's XML token stream, strictly: every component exactly
 * once, nothing unknown, each value of its declared type, polymorphic values only of registered
 * types. Everything wrong becomes an error naming the contents type and the field.
 *
 * <p>Jackson's XML parser reports attributes as fields that come before the child elements, so
 * the {@code type} attribute is the first field of a polymorphic element, and {@code xsi:nil}
 * arrives as a null token. Stateless apart from its registry; thread-safe.
 */
final class ContentsReader {

    private final ContentsTypes types;
    private final int maxTextLength;

    ContentsReader(ContentsTypes types, int maxTextLength) {
        this.types = types;
        this.maxTextLength = maxTextLength;
    }

    /**
     * Reads the {@code <contents>} element; the parser is at its first token.
     *
     * @throws MessageFormatException naming the contents type and the field
     */
    Contents readContents(JsonParser parser) throws IOException {
        if (parser.currentToken() != JsonToken.START_OBJECT) {
            throw new MessageFormatException("<contents> has no type attribute; write <contents type=\"name\">");
        }
        String name = readTypeAttribute(parser);
        if (name == null) {
            throw new MessageFormatException("<contents> has no type attribute; write <contents type=\"name\">");
        }
        Class<? extends Contents> type = types.typeOf(name);
        if (type == null) {
            throw new MessageFormatException(unknownType(name));
        }
        try {
            return (Contents) readRecordBody(parser, RecordShape.of(type));
        } catch (FieldError e) {
            throw new MessageFormatException("contents type '" + name + "': " + e.describe(), e.getCause());
        }
    }

    private String unknownType(String name) {
        return "unknown contents type '" + name + "'; registered types are " + types.names();
    }

    /** Consumes the type attribute, leaving the parser on it; null if the element has none. */
    private static String readTypeAttribute(JsonParser parser) throws IOException {
        if (parser.nextToken() != JsonToken.FIELD_NAME || !Wire.TYPE.equals(parser.currentName())) {
            return null;
        }
        JsonToken value = parser.nextToken();
        return value == JsonToken.VALUE_STRING ? Scalars.strip(parser.getText()) : null;
    }

    /**
     * Reads the fields of a record up to the end of its element and builds it. The parser is at
     * the element's start, or on the last attribute already consumed.
     */
    private Object readRecordBody(JsonParser parser, RecordShape shape) throws IOException {
        Object[] arguments = new Object[shape.size()];
        boolean[] seen = new boolean[shape.size()];
        int next = 0;
        for (JsonToken token = parser.nextToken(); token != JsonToken.END_OBJECT; token = parser.nextToken()) {
            if (token != JsonToken.FIELD_NAME) {
                throw new FieldError("unexpected " + token + " in " + shape.type.getSimpleName());
            }
            String name = parser.currentName();
            if (name.isEmpty()) {
                skipWhitespaceText(parser, shape.type.getSimpleName());
                continue;
            }
            int index = shape.indexOf(name, next);
            if (index < 0) {
                throw new FieldError(shape.type.getSimpleName() + " has no field '" + name + "'");
            }
            if (seen[index]) {
                throw new FieldError("field '" + name + "' appears twice");
            }
            parser.nextToken();
            try {
                arguments[index] = readValue(parser, shape.types[index]);
            } catch (FieldError e) {
                throw e.inField(name);
            }
            seen[index] = true;
            next = index + 1;
        }
        for (int i = 0; i < seen.length; i++) {
            if (!seen[i]) {
                throw new FieldError("missing field '" + shape.names[i] + "'");
            }
        }
        return construct(shape, arguments);
    }

    private static Object construct(RecordShape shape, Object[] arguments) {
        try {
            return shape.construct(arguments);
        } catch (NullPointerException e) {
            throw new FieldError("invalid " + shape.type.getSimpleName() + ": a field that must not be null is nil ("
                    + e.getMessage() + ")");
        } catch (RuntimeException e) {
            throw new FieldError("invalid " + shape.type.getSimpleName() + ": " + e.getMessage());
        }
    }

    /** Reads one value; the parser is at its first token. */
    private Object readValue(JsonParser parser, ValueType type) throws IOException {
        if (parser.currentToken() == JsonToken.VALUE_NULL) {
            if (!type.nullable()) {
                throw new FieldError("nil is not allowed for a " + type.describe());
            }
            return null;
        }
        return switch (type) {
            case Scalar scalar -> Scalars.parse(scalar.kind(), text(parser, type));
            case EnumType enumType -> enumConstant(enumType, text(parser, type));
            case ArrayType array -> Scalars.parseArray(array.kind(), text(parser, type));
            case RecordType record -> readRecord(parser, RecordShape.of(record.type()));
            case ContentsType contents -> readPolymorphic(parser, contents.declared());
            case ListType list -> readList(parser, list);
        };
    }

    private static Object enumConstant(EnumType type, String text) {
        Object constant = type.constants().get(Scalars.strip(text));
        if (constant == null) {
            throw new FieldError(Scalars.quote(text) + " is not one of " + type.allowed());
        }
        return constant;
    }

    private Object readRecord(JsonParser parser, RecordShape shape) throws IOException {
        if (parser.currentToken() == JsonToken.START_OBJECT) {
            return readRecordBody(parser, shape);
        }
        // <field/> or whitespace only: a record without components, or one missing them all.
        String text = text(parser, new RecordType(shape.type));
        if (!Scalars.isBlank(text)) {
            throw new FieldError("expected the elements of " + shape.type.getSimpleName() + ", found text "
                    + Scalars.quote(text));
        }
        if (shape.size() > 0) {
            throw new FieldError("missing field '" + shape.names[0] + "'");
        }
        return construct(shape, new Object[0]);
    }

    private Object readPolymorphic(JsonParser parser, Class<?> declared) throws IOException {
        String name = parser.currentToken() == JsonToken.START_OBJECT ? readTypeAttribute(parser) : null;
        if (name == null) {
            throw new FieldError("has no type attribute; a " + declared.getSimpleName()
                    + " field needs the registered type name, as in <field type=\"name\">");
        }
        Class<? extends Contents> type = types.typeOf(name);
        if (type == null) {
            throw new FieldError(unknownType(name));
        }
        if (!declared.isAssignableFrom(type)) {
            throw new FieldError("contents type '" + name + "' is a " + type.getSimpleName() + ", which is not a "
                    + declared.getSimpleName());
        }
        return readRecordBody(parser, RecordShape.of(type));
    }

    private List<Object> readList(JsonParser parser, ListType list) throws IOException {
        if (parser.currentToken() != JsonToken.START_OBJECT) {
            String text = text(parser, list);
            if (!Scalars.isBlank(text)) {
                throw new FieldError("expected <item> elements, found text " + Scalars.quote(text));
            }
            return List.of();
        }
        var values = new ArrayList<>();
        for (JsonToken token = parser.nextToken(); token != JsonToken.END_OBJECT; token = parser.nextToken()) {
            if (token != JsonToken.FIELD_NAME) {
                throw new FieldError("unexpected " + token + " in a list");
            }
            String name = parser.currentName();
            if (name.isEmpty()) {
                skipWhitespaceText(parser, "a list");
                continue;
            }
            if (!Wire.ITEM.equals(name)) {
                throw new FieldError("expected <item> elements in a list, found <" + name + ">");
            }
            parser.nextToken();
            try {
                values.add(readValue(parser, list.element()));
            } catch (FieldError e) {
                throw e.inItem(values.size());
            }
        }
        return Collections.unmodifiableList(values);
    }

    /** Text between child elements; only whitespace (indentation) is allowed there. */
    private static void skipWhitespaceText(JsonParser parser, String where) throws IOException {
        parser.nextToken();
        String text = parser.getText();
        if (text != null && !Scalars.isBlank(text)) {
            throw new FieldError("unexpected text " + Scalars.quote(text) + " in " + where);
        }
    }

    private String text(JsonParser parser, ValueType type) throws IOException {
        JsonToken token = parser.currentToken();
        if (token == JsonToken.START_OBJECT) {
            throw new FieldError("expected text for a " + type.describe() + ", found child elements or attributes");
        }
        if (token == null || !token.isScalarValue()) {
            throw new FieldError("expected text for a " + type.describe() + ", found " + token);
        }
        String text = parser.getText();
        // Woodstox bounds each text segment; text split by CDATA sections is joined again here.
        if (text.length() > maxTextLength) {
            throw new FieldError(tooLong(text.length(), maxTextLength));
        }
        return text;
    }

    static String tooLong(int length, int maxTextLength) {
        return "text longer than maxTextLength=" + maxTextLength + " (" + length + " chars)";
    }
}
