package io.etherware.services.management;

import io.etherware.core.component.Component;
import java.nio.file.Path;
import java.util.Objects;

/**
 * The new logic an upgrade installs: a class from the managed node's class path, or from a jar in
 * one of its allowlisted directories, signed by a key the node trusts (see {@link ManagementConfig}).
 *
 * <h2>The class's contract</h2>
 * <ul>
 *   <li>a public, non-abstract class (top level or {@code static} nested) that implements
 *       {@link Component};</li>
 *   <li>a public no-arg constructor, or, when the upgrade carries a {@link #configuration()}, a
 *       public constructor taking that one {@code String} (e.g. gains as text);</li>
 *   <li>it takes the old logic's state in {@link Component#restore}, which may check
 *       {@code state.schemaVersion()} to convert an old layout; throwing there rolls the upgrade
 *       back, and the old logic resumes. {@code restore} and {@code onStart} run inside the swap,
 *       on a dispatcher, while the component's messages wait: keep them short and put slow
 *       preparation in the constructor, which runs before the swap on the service's worker.</li>
 * </ul>
 * The node constructs one instance off its dispatchers before the swap, and uses the constructor
 * again for later restarts by the component's supervision policy.
 *
 * <h2>Classes from a jar</h2>
 * Each upgrade from a jar gets a class loader of its own whose parent is the node's class loader.
 * It looks in the jar first, so a jar may carry a new version of a class the node already has, with
 * two exceptions that keep shared types shared: the platform, slf4j and the Etherware core, rt and
 * services packages always come from the node, and so does any
 * {@link io.etherware.core.message.Contents} type the node already has (message contents and
 * component states), even if the jar carries a copy of it.
 *
 * <p>Immutable; safe to share between threads.
 *
 * @param className     the class's binary name
 * @param jar           the jar to load it from (a path on the managed node), or null for the class path
 * @param configuration the argument of the class's {@code (String)} constructor, or null to use
 *                      its no-arg constructor
 */
public record Implementation(String className, Path jar, String configuration) {

    /**
     * Checks that a class name is given; the rest is checked by the managed node.
     *
     * @throws NullPointerException if {@code className} is null
     */
    public Implementation {
        Objects.requireNonNull(className, "className");
    }

    /**
     * A class on the managed node's class path, by name.
     *
     * @param className the class's binary name, e.g. {@code com.example.ControllerV2}
     * @return the implementation, with its no-arg constructor
     */
    public static Implementation ofClass(String className) {
        return new Implementation(className, null, null);
    }

    /**
     * A class on the managed node's class path (this JVM's class name for it).
     *
     * @param type the class; the managed node loads it by name from its own class path
     * @return the implementation, with its no-arg constructor
     */
    public static Implementation ofClass(Class<? extends Component> type) {
        return ofClass(type.getName());
    }

    /**
     * A class in a jar on the managed node; the jar must lie in an allowlisted directory there and
     * be signed, entirely, by a key the node trusts.
     *
     * @param jar       the jar's path on the managed node
     * @param className the class's binary name
     * @return the implementation, with its no-arg constructor
     */
    public static Implementation fromJar(Path jar, String className) {
        return new Implementation(className, Objects.requireNonNull(jar, "jar"), null);
    }

    /**
     * This implementation, constructed with {@code value} as its configuration.
     *
     * @param value the argument of the class's {@code (String)} constructor, e.g. gains as text
     * @return a copy with that configuration
     * @throws NullPointerException if {@code value} is null
     */
    public Implementation withConfiguration(String value) {
        return new Implementation(className, jar, Objects.requireNonNull(value, "configuration"));
    }

    @Override
    public String toString() {
        return className + (jar == null ? "" : " from " + jar) + (configuration == null ? "" : " (configured)");
    }
}
