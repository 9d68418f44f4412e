package io.etherware.deploy;

import io.etherware.core.message.Profile;
import io.etherware.deploy.internal.XmlElement;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.LinkedHashSet;
import java.util.Map;
import java.util.Set;

/**
 * The {@code <setting name="..." value="..."/>}s of one {@code <component>}, read by its
 * {@link ComponentFactory} with typed getters. A missing required setting, or a value that is not
 * of the asked type or range, throws a {@link DeploymentException} naming the setting, its line
 * and what would do. Remembers which settings were read, so that the launcher can report the
 * unread ones (misspelt names). Used by one thread.
 */
public final class Settings {

    private final Path file;
    private final XmlElement component;
    private final Map<String, XmlElement> byName;
    private final Set<String> read = new LinkedHashSet<>();

    Settings(Path file, XmlElement component) throws DeploymentException {
        this.file = file;
        this.component = component;
        var settings = new LinkedHashMap<String, XmlElement>();
        for (XmlElement setting : component.children("setting")) {
            String name = setting.attributes().get("name");
            XmlElement earlier = settings.putIfAbsent(name, setting);
            if (earlier != null) {
                throw new DeploymentException(file, setting.line(), setting.column(), "<setting name=\"" + name
                        + "\"> is given twice (first on line " + earlier.line() + "); keep one", null);
            }
        }
        byName = Collections.unmodifiableMap(settings);
    }

    /**
     * The directory of the deployment file, against which relative paths resolve.
     *
     * @return the directory
     */
    public Path directory() {
        Path parent = file.toAbsolutePath().getParent();
        return parent != null ? parent : Path.of("").toAbsolutePath();
    }

    /**
     * Whether the file gives setting {@code name} (does not count as reading it).
     *
     * @param name the setting's name
     * @return true if given
     */
    public boolean has(String name) {
        return byName.containsKey(name);
    }

    /**
     * A required setting's text.
     *
     * @param name the setting's name
     * @return its value
     * @throws DeploymentException if the file does not give it
     */
    public String string(String name) throws DeploymentException {
        read.add(name);
        XmlElement setting = byName.get(name);
        if (setting == null) {
            throw new DeploymentException(file, component.line(), component.column(), "<component profile=\""
                    + component.attributes().get("profile") + "\"> needs <setting name=\"" + name
                    + "\" value=\"...\"/>", null);
        }
        return setting.attributes().get("value");
    }

    /**
     * An optional setting's text.
     *
     * @param name         the setting's name
     * @param defaultValue what applies when the file does not give it
     * @return its value, or {@code defaultValue}
     */
    public String string(String name, String defaultValue) {
        read.add(name);
        XmlElement setting = byName.get(name);
        return setting == null ? defaultValue : setting.attributes().get("value");
    }

    /**
     * An optional whole-number setting within a range.
     *
     * @param name         the setting's name
     * @param defaultValue what applies when the file does not give it
     * @param min          the smallest accepted
     * @param max          the largest accepted
     * @return its value, or {@code defaultValue}
     * @throws DeploymentException if the value is not a whole number in range
     */
    public long integer(String name, long defaultValue, long min, long max) throws DeploymentException {
        String text = string(name, null);
        if (text == null) {
            return defaultValue;
        }
        try {
            long value = Long.parseLong(text.strip().replace("_", ""));
            if (value >= min && value <= max) {
                return value;
            }
        } catch (NumberFormatException e) {
            // reported below
        }
        throw invalid(name, "write a whole number within [" + min + ", " + max + "]");
    }

    /**
     * An optional decimal setting within a range.
     *
     * @param name         the setting's name
     * @param defaultValue what applies when the file does not give it
     * @param min          the smallest accepted
     * @param max          the largest accepted
     * @return its value, or {@code defaultValue}
     * @throws DeploymentException if the value is not a finite number in range
     */
    public double number(String name, double defaultValue, double min, double max) throws DeploymentException {
        String text = string(name, null);
        if (text == null) {
            return defaultValue;
        }
        try {
            double value = Double.parseDouble(text.strip());
            if (value >= min && value <= max) {
                return value;
            }
        } catch (NumberFormatException e) {
            // reported below
        }
        throw invalid(name, "write a number within [" + min + ", " + max + "]");
    }

    /**
     * An optional duration setting, written like the schema's durations ({@code 15ms}).
     *
     * @param name         the setting's name
     * @param defaultValue what applies when the file does not give it
     * @return its value, or {@code defaultValue}
     * @throws DeploymentException if the value is not a positive duration with a unit
     */
    public Duration duration(String name, Duration defaultValue) throws DeploymentException {
        String text = string(name, null);
        if (text == null) {
            return defaultValue;
        }
        try {
            return Durations.parse(text);
        } catch (IllegalArgumentException e) {
            throw invalid(name, e.getMessage());
        }
    }

    /**
     * An optional profile setting ({@code role} or {@code role[key=value,...]}).
     *
     * @param name         the setting's name
     * @param defaultValue what applies when the file does not give it
     * @return its value, or {@code defaultValue}
     * @throws DeploymentException if the value is not a profile
     */
    public Profile profile(String name, Profile defaultValue) throws DeploymentException {
        String text = string(name, null);
        if (text == null) {
            return defaultValue;
        }
        try {
            return Profile.parse(text.strip());
        } catch (IllegalArgumentException e) {
            throw invalid(name, e.getMessage() + "; write a role or role[key=value,...]");
        }
    }

    /**
     * An error about setting {@code name}'s value, for a factory's own checks.
     *
     * @param name the setting's name
     * @param fix  what is wrong and what would do
     * @return the exception to throw, naming the setting's line and value
     */
    public DeploymentException invalid(String name, String fix) {
        XmlElement setting = byName.get(name);
        XmlElement at = setting != null ? setting : component;
        String value = setting != null ? setting.attributes().get("value") : null;
        return new DeploymentException(file, at.line(), at.column(), "<setting name=\"" + name + "\""
                + (value != null ? " value=\"" + value + "\"" : "") + ">: " + fix, null);
    }

    /** The settings the file gives that were not read, with their elements. */
    Map<String, XmlElement> unread() {
        var unread = new LinkedHashMap<>(byName);
        unread.keySet().removeAll(read);
        return unread;
    }

    /** The names read so far (given or not), for the message about an unread one. */
    Set<String> readNames() {
        return Collections.unmodifiableSet(read);
    }
}
