package io.etherware.core.message;

import java.lang.reflect.Modifier;
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
 * <p>There is no process-wide registry: each node has its own ({@code NodeConfig.contentsTypes},
 * {@code Kernel.contentsTypes()}) and each codec is given one. A registry starts with the
 * built-in types {@code empty}, {@code text} and {@code tick}; the code that builds a node or a
 * codec registers the types it will carry, explicitly, with each module's
 * {@code registerContents(ContentsTypes)}: what decodes never depends on which classes happened
 * to load.
 *
 * <p>The codec reads records by reflection from module {@code io.etherware.core}, so registration
 * checks that it can: a public record in a package its module exports, or any record in a package
 * its module opens to {@code io.etherware.core}. A record that the codec could not read is refused
 * here, at once, rather than failing every message that carries it later.
 */
public final class ContentsTypes {

    /** Allowed type names: a lower-case letter, then letters, digits, '.', '_' or '-'. */
    public static final String TYPE_NAME_PATTERN = "[a-z][A-Za-z0-9_.-]*";
    private static final Pattern TYPE_NAME = Pattern.compile(TYPE_NAME_PATTERN);

    private final Map<String, Class<? extends Contents>> byName = new ConcurrentHashMap<>();
    private final Map<Class<? extends Contents>, String> byType = new ConcurrentHashMap<>();

    /** A new registry holding only the built-in types. */
    public ContentsTypes() {
        register("empty", Empty.class);
        register("text", Text.class);
        register("tick", Tick.class);
    }

    /**
     * Registers {@code type} under {@code name}.
     *
     * @param name the type's name on the wire, matching {@link #TYPE_NAME_PATTERN}
     * @param type the record carried under that name
     * @param <T>  the record type
     * @return this registry, for chaining
     * @throws IllegalArgumentException if the name is malformed, the type is not a record, the codec
     *                                  could not read it (its package is neither exported with the
     *                                  record public, nor opened to {@code io.etherware.core}), or
     *                                  name or type is already registered with another partner
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
        requireReadable(type);
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
     * Refuses a record the codec, in module {@code io.etherware.core}, could not read by reflection:
     * in a named module, its package must be opened to {@code io.etherware.core}, or the record
     * (and every class enclosing it) public in a package exported to all. Only the record itself is
     * checked; a record nested in its components is checked when the codec first meets it.
     */
    private static void requireReadable(Class<?> type) {
        Module module = type.getModule();
        Module codec = ContentsTypes.class.getModule();
        String pkg = type.getPackageName();
        if (!module.isNamed() || module.isOpen(pkg, codec)) {
            return;
        }
        boolean publicAllTheWay = true;
        for (Class<?> c = type; c != null; c = c.getEnclosingClass()) {
            publicAllTheWay &= Modifier.isPublic(c.getModifiers());
        }
        // Unqualified: without an open package the codec falls back to public access, which reaches
        // only packages exported to everyone ("exports p to io.etherware.core" is not enough).
        if (publicAllTheWay && module.isExported(pkg)) {
            return;
        }
        throw new IllegalArgumentException("contents type " + type.getName() + " cannot be read by the codec: module "
                + module.getName() + " " + (module.isExported(pkg) ? "exports" : "neither exports to all nor opens")
                + " package " + pkg + (publicAllTheWay ? "" : " and the record is not public")
                + "; add 'opens " + pkg + " to io.etherware.core;' to " + module.getName() + "'s module-info.java"
                + (publicAllTheWay ? "" : " (or make the record public in an exported package)"));
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
