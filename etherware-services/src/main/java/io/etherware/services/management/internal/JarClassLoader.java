package io.etherware.services.management.internal;

import io.etherware.core.message.Contents;
import java.io.IOException;
import java.net.MalformedURLException;
import java.net.URL;
import java.net.URLClassLoader;
import java.nio.file.Path;

/**
 * The class loader of one upgrade from a jar, reading the node's private, verified copy of it
 * (deleted when the loader is closed). It looks in the jar first, so the jar may carry a new
 * version of a class the node already has, except for the types that must stay shared with the
 * node: the platform, slf4j and the Etherware core, rt and services packages always come from the
 * parent, and so does any {@link Contents} type the parent has (a state record or message contents
 * bundled into the jar would otherwise be a second, incompatible class of the same name).
 *
 * <p>Thread-safety: parallel capable; classes are loaded under the per-name lock of
 * {@link ClassLoader#getClassLoadingLock}.
 */
final class JarClassLoader extends URLClassLoader {

    static {
        registerAsParallelCapable();
    }

    private static final String[] NODE_PACKAGES = {
        "java.", "javax.", "jdk.", "sun.", "com.sun.", "org.slf4j.",
        "io.etherware.core.", "io.etherware.rt.", "io.etherware.services."
    };

    private final Path copy;

    /**
     * @param copy the verified copy to load from; this loader deletes it when closed
     * @param jar  the jar it is a copy of, for the loader's name
     */
    JarClassLoader(Path copy, Path jar, ClassLoader parent) throws MalformedURLException {
        super("etherware-upgrade[" + jar.getFileName() + "]", new URL[] {copy.toUri().toURL()}, parent);
        this.copy = copy;
    }

    @Override
    public void close() throws IOException {
        try {
            super.close();
        } finally {
            PluginVerifier.deleteQuietly(copy);
        }
    }

    @Override
    protected Class<?> loadClass(String name, boolean resolve) throws ClassNotFoundException {
        synchronized (getClassLoadingLock(name)) {
            Class<?> type = findLoadedClass(name);
            if (type == null) {
                type = isNodePackage(name) ? getParent().loadClass(name) : jarFirst(name);
            }
            if (resolve) {
                resolveClass(type);
            }
            return type;
        }
    }

    private Class<?> jarFirst(String name) throws ClassNotFoundException {
        Class<?> nodes = parentClassOrNull(name);
        if (nodes != null && Contents.class.isAssignableFrom(nodes)) {
            return nodes;
        }
        try {
            return findClass(name);
        } catch (ClassNotFoundException notInJar) {
            if (nodes != null) {
                return nodes;
            }
            throw notInJar;
        }
    }

    private Class<?> parentClassOrNull(String name) {
        try {
            return getParent().loadClass(name);
        } catch (ClassNotFoundException e) {
            return null;
        }
    }

    @Override
    public URL getResource(String name) {
        URL inJar = findResource(name);
        return inJar != null ? inJar : super.getResource(name);
    }

    private static boolean isNodePackage(String name) {
        for (String prefix : NODE_PACKAGES) {
            if (name.startsWith(prefix)) {
                return true;
            }
        }
        return false;
    }
}
