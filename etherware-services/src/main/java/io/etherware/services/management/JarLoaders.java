package io.etherware.services.management;

import io.etherware.core.message.Profile;
import io.etherware.services.management.internal.ImplementationLoader;
import java.net.URLClassLoader;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;

/**
 * The jar class loader behind each component of the node upgraded or migrated in from a jar,
 * closed when the logic it loaded is replaced or leaves; shared by the instances that a management
 * service's restarts make.
 *
 * <p>Thread-safety: any thread (a concurrent map); takes no lock.
 */
final class JarLoaders {

    private final Map<Profile, URLClassLoader> loaders = new ConcurrentHashMap<>();

    /**
     * After a successful swap (or hand-over, or migration away): the jar loader of the replaced
     * logic is no longer needed. {@code newLoader} is the new logic's, or null when it came from the
     * class path or the component left.
     */
    void installed(Profile profile, URLClassLoader newLoader) {
        URLClassLoader previous = newLoader == null ? loaders.remove(profile) : loaders.put(profile, newLoader);
        ImplementationLoader.closeQuietly(previous);
    }
}
