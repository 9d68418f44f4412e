package io.etherware.core.message;

import java.util.Map;
import java.util.Objects;
import java.util.Set;
import java.util.TreeSet;
import java.util.concurrent.ConcurrentHashMap;
import java.util.regex.Pattern;

/**
 * The registry of payload types: a name on the wire for each {@link Contents} record.
 *
 * <p>Decoding only ever instantiates a type registered here, so a peer cannot make this JVM load
 * an arbitrary class. Registration is idempotent for the same pair and an error for a conflicting
 * one. Thread-safe; lookups are lock-free.
 *
 * <p>{@link #shared()} is the process-wide registry that codecs use by default; it starts with
 * the built-in types {@code empty}, {@code text} and {@code tick}. Modules register their own
 * types once, typically from a static initializer or at node start.
 */
public final class ContentsTypes {

    /** Allowed type names: a lower-case letter, then letters, digits, '.', '_' or '-'. */
    public static final String TYPE_NAME_PATTERN = "[a-z][A-Za-z0-9_.-]*";
    private static final Pattern TYPE_NAME = Pattern.compile(TYPE_NAME_PATTERN);

    private static final ContentsTypes SHARED = new ContentsTypes();

    private final Map<String, Class<? extends Contents>> byName = new ConcurrentHashMap<>();
    private final Map<Class<? extends Contents>, String> byType = new ConcurrentHashMap<>();

    /** A new registry holding only the built-in types. */
    public ContentsTypes() {
        register("empty", Empty.class);
        register("text", Text.class);
        register("tick", Tick.class);
    }

    /** {@return the process-wide registry, which codecs use unless given another} */
    public static ContentsTypes shared() {
        return SHARED;
    }

    /**
     * Registers {@code type} under {@code name}.
     *
     * @param <T>  the record type
     * @param name the wire name; must match {@link #TYPE_NAME_PATTERN}
     * @param type the record class to register
     * @return this registry, to chain registrations
     * @throws IllegalArgumentException if the name is malformed, the type is not a record, or
     *                                  either is already registered with another partner
     */
    public synchronized <T extends Record & Contents> ContentsTypes register(String name, Class<T> type) {
        return registerAny(name, type);
    }

    synchronized ContentsTypes registerAny(String name, Class<? extends Contents> type) {
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(type, "type");
        if (!TYPE_NAME.matcher(name).matches()) {
            throw new IllegalArgumentException("contents type name '" + name + "' must match " + TYPE_NAME_PATTERN);
        }
        if (!type.isRecord()) {
            throw new IllegalArgumentException("contents type " + type.getName() + " must be a record");
        }
        Class<? extends Contents> existing = byName.get(name);
        if (existing != null && existing != type) {
            throw new IllegalArgumentException("contents type name '" + name + "' is already registered for "
                    + existing.getName() + "; cannot register " + type.getName());
        }
        String existingName = byType.get(type);
        if (existingName != null && !existingName.equals(name)) {
            throw new IllegalArgumentException("contents type " + type.getName() + " is already registered as '"
                    + existingName + "'; cannot register it as '" + name + "'");
        }
        byName.put(name, type);
        byType.put(type, name);
        return this;
    }

    /**
     * {@return the record type registered under {@code name}, or null if there is none}
     *
     * @param name a wire name
     */
    public Class<? extends Contents> typeOf(String name) {
        return byName.get(name);
    }

    /**
     * The wire name of {@code type}.
     *
     * @param type a contents record class
     * @return the name it was registered under
     * @throws MessageFormatException if the type was never registered
     */
    public String nameOf(Class<? extends Contents> type) {
        String name = byType.get(type);
        if (name == null) {
            throw new MessageFormatException("contents type " + type.getName()
                    + " is not registered; call ContentsTypes.register(name, " + type.getSimpleName() + ".class)");
        }
        return name;
    }

    /**
     * {@return whether {@code type} has a wire name}
     *
     * @param type a contents record class
     */
    public boolean isRegistered(Class<? extends Contents> type) {
        return byType.containsKey(type);
    }

    /** {@return the registered names, sorted; a copy, unaffected by later registrations} */
    public Set<String> names() {
        return new TreeSet<>(byName.keySet());
    }
}
