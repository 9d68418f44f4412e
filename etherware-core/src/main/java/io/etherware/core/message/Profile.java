package io.etherware.core.message;

import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.Objects;
import java.util.SequencedMap;
import java.util.regex.Pattern;

/**
 * A semantic address (paper Section III-C): a role plus an ordered set of attributes, such as
 * "controller of car 1", written {@code controller[car=1]}.
 *
 * <p>The text form is {@code role} or {@code role[key=value,key=value]}; {@link #parse} and
 * {@link #toString} are exact inverses. Roles and keys match {@value #NAME_PATTERN}; values match
 * {@value #VALUE_PATTERN}. Attribute order is kept for display, but two profiles are equal when
 * their roles and attribute maps are equal, whatever the order.
 *
 * @param role       what the component is, e.g. {@code controller}
 * @param attributes which one, e.g. {@code car=1}; unmodifiable, insertion-ordered
 */
public record Profile(String role, SequencedMap<String, String> attributes) {

    /** Roles, attribute keys and node ids. */
    public static final String NAME_PATTERN = "[A-Za-z0-9_][A-Za-z0-9_.-]*";
    /** Attribute values. */
    public static final String VALUE_PATTERN = "[A-Za-z0-9_.:/@+-]+";

    private static final Pattern NAME = Pattern.compile(NAME_PATTERN);
    private static final Pattern VALUE = Pattern.compile(VALUE_PATTERN);

    /**
     * Checks the role and every attribute, and keeps an unmodifiable copy of the attributes.
     *
     * @throws IllegalArgumentException naming the part if the role, a key or a value does not
     *                                  match its pattern
     */
    public Profile {
        Objects.requireNonNull(role, "role");
        Objects.requireNonNull(attributes, "attributes");
        if (!NAME.matcher(role).matches()) {
            throw new IllegalArgumentException("profile role '" + role + "' must match " + NAME_PATTERN);
        }
        var copy = new LinkedHashMap<String, String>();
        attributes.forEach((key, value) -> {
            if (key == null || !NAME.matcher(key).matches()) {
                throw new IllegalArgumentException("profile attribute key '" + key + "' must match " + NAME_PATTERN);
            }
            if (value == null || !VALUE.matcher(value).matches()) {
                throw new IllegalArgumentException(
                        "profile attribute " + key + "='" + value + "' must match " + VALUE_PATTERN);
            }
            copy.put(key, value);
        });
        attributes = Collections.unmodifiableSequencedMap(copy);
    }

    /**
     * A profile with a role and no attributes.
     *
     * @param role the role; must match {@link #NAME_PATTERN}
     * @return the profile {@code role}
     * @throws IllegalArgumentException if the role is malformed
     */
    public static Profile of(String role) {
        return new Profile(role, new LinkedHashMap<>());
    }

    /**
     * A profile from a role and alternating keys and values: {@code of("controller", "car", "1")}.
     *
     * @param role          the role; must match {@link #NAME_PATTERN}
     * @param keysAndValues an even number of strings: key, value, key, value, in display order
     * @return the profile
     * @throws IllegalArgumentException if the strings are not pairs, a key is given twice, or a
     *                                  part does not match its pattern
     */
    public static Profile of(String role, String... keysAndValues) {
        if (keysAndValues.length % 2 != 0) {
            throw new IllegalArgumentException("Profile.of needs key/value pairs, got " + keysAndValues.length + " strings");
        }
        var attributes = new LinkedHashMap<String, String>();
        for (int i = 0; i < keysAndValues.length; i += 2) {
            if (attributes.put(keysAndValues[i], keysAndValues[i + 1]) != null) {
                throw new IllegalArgumentException("profile attribute '" + keysAndValues[i] + "' given twice");
            }
        }
        return new Profile(role, attributes);
    }

    /**
     * Parses the text form, {@code role} or {@code role[key=value,...]}.
     *
     * @param text the text form, as {@link #toString()} writes it
     * @return the profile it describes
     * @throws IllegalArgumentException naming the text and what is wrong with it
     */
    public static Profile parse(String text) {
        Objects.requireNonNull(text, "text");
        int open = text.indexOf('[');
        if (open < 0) {
            return new Profile(requireName(text, text, "role"), new LinkedHashMap<>());
        }
        if (!text.endsWith("]")) {
            throw new IllegalArgumentException("profile '" + text + "': '[' without closing ']' at the end");
        }
        String role = requireName(text, text.substring(0, open), "role");
        String body = text.substring(open + 1, text.length() - 1);
        var attributes = new LinkedHashMap<String, String>();
        if (!body.isEmpty()) {
            for (String pair : body.split(",", -1)) {
                int eq = pair.indexOf('=');
                if (eq < 0) {
                    throw new IllegalArgumentException("profile '" + text + "': attribute '" + pair + "' is not key=value");
                }
                String key = requireName(text, pair.substring(0, eq), "attribute key");
                String value = pair.substring(eq + 1);
                if (!VALUE.matcher(value).matches()) {
                    throw new IllegalArgumentException("profile '" + text + "': attribute value '" + value
                            + "' of '" + key + "' must match " + VALUE_PATTERN);
                }
                if (attributes.put(key, value) != null) {
                    throw new IllegalArgumentException("profile '" + text + "': attribute '" + key + "' given twice");
                }
            }
        } else {
            throw new IllegalArgumentException("profile '" + text + "': empty attribute list; write just the role");
        }
        return new Profile(role, attributes);
    }

    /**
     * {@return whether {@code text} matches {@link #NAME_PATTERN}, i.e. is a valid role, key or
     * node id} Allocation-free, for checks on the per-message path.
     *
     * @param text the text to check; null is not a name
     */
    public static boolean isName(String text) {
        // Same language as NAME_PATTERN, without a Matcher: MessageId checks its node id with
        // this on every message, so it must not allocate (136 bytes per call with the regex).
        if (text == null || text.isEmpty()) {
            return false;
        }
        for (int i = 0; i < text.length(); i++) {
            char c = text.charAt(i);
            boolean nameChar = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'
                    || (i > 0 && (c == '.' || c == '-'));
            if (!nameChar) {
                return false;
            }
        }
        return true;
    }

    /**
     * {@return this profile with one more attribute (or a replaced value, which keeps its place)}
     * A new attribute is appended at the end.
     *
     * @param key   the attribute key; must match {@link #NAME_PATTERN}
     * @param value the attribute value; must match {@link #VALUE_PATTERN}
     * @throws IllegalArgumentException if the key or the value is malformed
     */
    public Profile with(String key, String value) {
        var copy = new LinkedHashMap<>(attributes);
        copy.put(key, value);
        return new Profile(role, copy);
    }

    /**
     * {@return whether this profile satisfies a query: same role, and every attribute of the query
     * present here with the same value (this profile may have more)}
     *
     * @param query the profile used as a query
     */
    public boolean matches(Profile query) {
        if (!role.equals(query.role)) {
            return false;
        }
        for (var entry : query.attributes.entrySet()) {
            if (!entry.getValue().equals(attributes.get(entry.getKey()))) {
                return false;
            }
        }
        return true;
    }

    @Override
    public String toString() {
        if (attributes.isEmpty()) {
            return role;
        }
        var text = new StringBuilder(role).append('[');
        boolean first = true;
        for (Map.Entry<String, String> entry : attributes.entrySet()) {
            if (!first) {
                text.append(',');
            }
            text.append(entry.getKey()).append('=').append(entry.getValue());
            first = false;
        }
        return text.append(']').toString();
    }

    private static String requireName(String text, String name, String what) {
        if (!NAME.matcher(name).matches()) {
            throw new IllegalArgumentException("profile '" + text + "': " + what + " '" + name + "' must match " + NAME_PATTERN);
        }
        return name;
    }
}
