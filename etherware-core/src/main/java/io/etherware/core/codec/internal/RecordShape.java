package io.etherware.core.codec.internal;

import io.etherware.core.message.MessageFormatException;

import java.lang.invoke.MethodHandle;
import java.lang.invoke.MethodHandles;
import java.lang.invoke.MethodType;
import java.lang.reflect.RecordComponent;
import java.util.HashMap;
import java.util.Map;

/**
 * What the codec knows about one record type: its components in declaration order, their wire
 * shapes, accessors and the canonical constructor, resolved once and cached per class.
 *
 * <p>Immutable and shared by all threads. Reflection uses a private lookup into the record's
 * package, which works on the class path and, on the module path, when the record's package is
 * open to {@code io.etherware.core}; a public record in an exported package needs no opening.
 */
final class RecordShape {

    private static final MethodType ACCESSOR = MethodType.methodType(Object.class, Object.class);
    private static final MethodType CONSTRUCTOR = MethodType.methodType(Object.class, Object[].class);

    private static final ClassValue<RecordShape> CACHE = new ClassValue<>() {
        @Override
        protected RecordShape computeValue(Class<?> type) {
            return new RecordShape(type);
        }
    };

    final Class<?> type;
    final String[] names;
    final ValueType[] types;
    private final MethodHandle[] accessors;
    private final MethodHandle constructor;
    private final Map<String, Integer> indexByName;

    private RecordShape(Class<?> type) {
        if (!type.isRecord()) {
            throw new MessageFormatException(type.getName() + " is not a record; contents and their nested types must be records");
        }
        this.type = type;
        MethodHandles.Lookup lookup = lookupFor(type);
        RecordComponent[] components = type.getRecordComponents();
        int count = components.length;
        names = new String[count];
        types = new ValueType[count];
        accessors = new MethodHandle[count];
        indexByName = new HashMap<>();
        Class<?>[] parameterTypes = new Class<?>[count];
        try {
            for (int i = 0; i < count; i++) {
                RecordComponent component = components[i];
                names[i] = component.getName();
                parameterTypes[i] = component.getType();
                try {
                    types[i] = ValueType.of(component.getGenericType());
                } catch (ValueType.UnsupportedTypeException e) {
                    throw new MessageFormatException("record " + type.getName() + " component '" + names[i]
                            + "' has type " + e.getMessage() + ", which the codec cannot carry; use primitives, boxes, "
                            + "String, enums, Profile, MessageId, records, Contents interfaces, List<...> of those, "
                            + "or int[], long[], double[], byte[]");
                }
                accessors[i] = lookup.unreflect(component.getAccessor()).asType(ACCESSOR);
                indexByName.put(names[i], i);
            }
            constructor = lookup.unreflectConstructor(type.getDeclaredConstructor(parameterTypes))
                    .asSpreader(Object[].class, count)
                    .asType(CONSTRUCTOR);
        } catch (ReflectiveOperationException e) {
            throw inaccessible(type, e);
        }
    }

    /** The cached shape of {@code type}. */
    static RecordShape of(Class<?> type) {
        return CACHE.get(type);
    }

    int size() {
        return names.length;
    }

    /** The component index for an element name, trying the expected position first. */
    int indexOf(String name, int expected) {
        if (expected < names.length && names[expected].equals(name)) {
            return expected;
        }
        Integer index = indexByName.get(name);
        return index == null ? -1 : index;
    }

    Object get(Object record, int index) {
        try {
            return accessors[index].invokeExact(record);
        } catch (RuntimeException | Error e) {
            throw e;
        } catch (Throwable e) {
            throw new IllegalStateException(e);
        }
    }

    /** Calls the canonical constructor; its own validation errors come out as they are. */
    Object construct(Object[] arguments) {
        try {
            return constructor.invokeExact(arguments);
        } catch (RuntimeException | Error e) {
            throw e;
        } catch (Throwable e) {
            throw new IllegalStateException(e);
        }
    }

    private static MethodHandles.Lookup lookupFor(Class<?> type) {
        Module codecModule = RecordShape.class.getModule();
        // A named module must read the record's module before it may look into it.
        codecModule.addReads(type.getModule());
        try {
            return MethodHandles.privateLookupIn(type, MethodHandles.lookup());
        } catch (IllegalAccessException notOpen) {
            // Not open to us: a public record in an exported package still works with public access.
            return MethodHandles.publicLookup();
        }
    }

    private static MessageFormatException inaccessible(Class<?> type, ReflectiveOperationException e) {
        String pkg = type.getPackageName();
        return new MessageFormatException("record " + type.getName() + " is not accessible to the codec; make it a "
                + "public record in an exported package, or add 'opens " + pkg
                + " to io.etherware.core;' to the module-info of " + type.getModule().getName(), e);
    }
}
