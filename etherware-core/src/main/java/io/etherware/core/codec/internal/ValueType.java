package io.etherware.core.codec.internal;

import io.etherware.core.message.Contents;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;

import java.lang.reflect.ParameterizedType;
import java.lang.reflect.Type;
import java.lang.reflect.WildcardType;
import java.util.Arrays;
import java.util.HashMap;
import java.util.List;
import java.util.Map;

/**
 * The wire shape of one record component, resolved once from its declared Java type.
 *
 * <p>Immutable; shared by all threads through {@link RecordShape}'s cache.
 */
sealed interface ValueType {

    /** Whether {@code null} is a legal value (false only for primitives). */
    default boolean nullable() {
        return true;
    }

    /** A short name for error messages, e.g. {@code long} or {@code List<Tick>}. */
    String describe();

    /** The scalar kinds, written as element text. */
    enum ScalarKind {
        BOOLEAN("boolean"), BYTE("byte"), SHORT("short"), CHAR("char"), INT("int"), LONG("long"),
        FLOAT("float"), DOUBLE("double"), STRING("String"), PROFILE("Profile"), MESSAGE_ID("MessageId");

        final String javaName;

        ScalarKind(String javaName) {
            this.javaName = javaName;
        }
    }

    /** A primitive, its box, a String, a Profile or a MessageId: element text. */
    record Scalar(ScalarKind kind, boolean primitive) implements ValueType {
        @Override
        public boolean nullable() {
            return !primitive;
        }

        @Override
        public String describe() {
            return kind.javaName;
        }
    }

    /** An enum: the constant's name as element text. */
    record EnumType(Class<?> type, Map<String, Object> constants) implements ValueType {
        static EnumType of(Class<?> type) {
            var constants = new HashMap<String, Object>();
            for (Object constant : type.getEnumConstants()) {
                constants.put(((Enum<?>) constant).name(), constant);
            }
            return new EnumType(type, Map.copyOf(constants));
        }

        @Override
        public String describe() {
            return type.getSimpleName();
        }

        String allowed() {
            return Arrays.toString(Arrays.stream(type.getEnumConstants()).map(c -> ((Enum<?>) c).name()).toArray());
        }
    }

    /** The primitive arrays: whitespace-separated numbers, or base64 for bytes. */
    enum ArrayKind {
        INT("int[]"), LONG("long[]"), DOUBLE("double[]"), BYTE("byte[]");

        final String javaName;

        ArrayKind(String javaName) {
            this.javaName = javaName;
        }
    }

    /** A primitive array. */
    record ArrayType(ArrayKind kind) implements ValueType {
        @Override
        public String describe() {
            return kind.javaName;
        }
    }

    /** A {@code List<E>}: one {@code <item>} element per entry. */
    record ListType(ValueType element) implements ValueType {
        @Override
        public String describe() {
            return "List<" + element.describe() + ">";
        }
    }

    /** A record whose type is known statically: its components as child elements. */
    record RecordType(Class<?> type) implements ValueType {
        @Override
        public String describe() {
            return type.getSimpleName();
        }
    }

    /**
     * A field declared as {@link Contents} or a sub-interface: polymorphic, so the element carries
     * the registered type name in a {@code type} attribute and is decoded only through the registry.
     */
    record ContentsType(Class<?> declared) implements ValueType {
        @Override
        public String describe() {
            return declared.getSimpleName();
        }
    }

    /**
     * Resolves the wire shape of a declared type.
     *
     * @throws UnsupportedTypeException if the codec cannot carry the type
     */
    static ValueType of(Type declared) {
        if (declared instanceof Class<?> type) {
            return ofClass(type);
        }
        if (declared instanceof ParameterizedType parameterized && parameterized.getRawType() == List.class) {
            return new ListType(of(parameterized.getActualTypeArguments()[0]));
        }
        if (declared instanceof WildcardType wildcard && wildcard.getLowerBounds().length == 0) {
            return of(wildcard.getUpperBounds()[0]);
        }
        throw new UnsupportedTypeException(declared.getTypeName());
    }

    private static ValueType ofClass(Class<?> type) {
        if (type.isPrimitive()) {
            return new Scalar(primitiveKind(type), true);
        }
        ScalarKind boxed = boxedKind(type);
        if (boxed != null) {
            return new Scalar(boxed, false);
        }
        if (type.isEnum()) {
            return EnumType.of(type);
        }
        if (type.isArray()) {
            Class<?> component = type.getComponentType();
            if (component == int.class) {
                return new ArrayType(ArrayKind.INT);
            } else if (component == long.class) {
                return new ArrayType(ArrayKind.LONG);
            } else if (component == double.class) {
                return new ArrayType(ArrayKind.DOUBLE);
            } else if (component == byte.class) {
                return new ArrayType(ArrayKind.BYTE);
            }
            throw new UnsupportedTypeException(type.getTypeName());
        }
        if (type.isInterface() && Contents.class.isAssignableFrom(type)) {
            return new ContentsType(type);
        }
        if (type.isRecord()) {
            return new RecordType(type);
        }
        throw new UnsupportedTypeException(type.getTypeName());
    }

    private static ScalarKind primitiveKind(Class<?> type) {
        if (type == boolean.class) {
            return ScalarKind.BOOLEAN;
        } else if (type == byte.class) {
            return ScalarKind.BYTE;
        } else if (type == short.class) {
            return ScalarKind.SHORT;
        } else if (type == char.class) {
            return ScalarKind.CHAR;
        } else if (type == int.class) {
            return ScalarKind.INT;
        } else if (type == long.class) {
            return ScalarKind.LONG;
        } else if (type == float.class) {
            return ScalarKind.FLOAT;
        } else if (type == double.class) {
            return ScalarKind.DOUBLE;
        }
        throw new UnsupportedTypeException(type.getTypeName());
    }

    private static ScalarKind boxedKind(Class<?> type) {
        if (type == Boolean.class) {
            return ScalarKind.BOOLEAN;
        } else if (type == Byte.class) {
            return ScalarKind.BYTE;
        } else if (type == Short.class) {
            return ScalarKind.SHORT;
        } else if (type == Character.class) {
            return ScalarKind.CHAR;
        } else if (type == Integer.class) {
            return ScalarKind.INT;
        } else if (type == Long.class) {
            return ScalarKind.LONG;
        } else if (type == Float.class) {
            return ScalarKind.FLOAT;
        } else if (type == Double.class) {
            return ScalarKind.DOUBLE;
        } else if (type == String.class) {
            return ScalarKind.STRING;
        } else if (type == Profile.class) {
            return ScalarKind.PROFILE;
        } else if (type == MessageId.class) {
            return ScalarKind.MESSAGE_ID;
        }
        return null;
    }

    /** A declared type the codec cannot carry; {@link RecordShape} turns it into a clear message. */
    final class UnsupportedTypeException extends RuntimeException {
        UnsupportedTypeException(String typeName) {
            super(typeName, null, false, false);
        }
    }
}
