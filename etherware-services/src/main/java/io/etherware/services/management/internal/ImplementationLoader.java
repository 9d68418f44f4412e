package io.etherware.services.management.internal;

import io.etherware.core.component.Component;
import io.etherware.core.message.ContentsTypes;
import io.etherware.services.management.ManagementFailure.Reason;
import io.etherware.services.management.UpgradeResult;
import java.io.IOException;
import java.lang.reflect.Constructor;
import java.lang.reflect.InvocationTargetException;
import java.lang.reflect.Method;
import java.lang.reflect.Modifier;
import java.net.URLClassLoader;
import java.nio.file.Files;
import java.nio.file.InvalidPathException;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.security.cert.X509Certificate;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.atomic.AtomicReference;
import java.util.function.Supplier;
import java.util.regex.Pattern;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Loads a new component logic for an upgrade: finds the class on the class path or in an
 * allowlisted jar signed by a trusted key (checked by a {@link PluginVerifier} before any of its
 * classes is defined; loaded through a {@link JarClassLoader} of its own, from the verified copy),
 * checks the implementation contract before running any of its code, and constructs the first
 * instance.
 *
 * <p>Thread-safety: immutable; {@link #load} may be called from any thread. It reads files and
 * runs the class's static initializer and constructor, so call it off the dispatchers.
 */
public final class ImplementationLoader {

    private static final Logger log = LoggerFactory.getLogger(ImplementationLoader.class);
    private static final Pattern BINARY_NAME =
            Pattern.compile("[\\p{L}_$][\\p{L}\\p{N}_$]*(\\.[\\p{L}_$][\\p{L}\\p{N}_$]*)*");

    private final List<Path> allowlist;
    private final PluginVerifier verifier;
    private final ClassLoader classLoader;
    private final ContentsTypes contentsTypes;

    /**
     * @param allowlist      canonical directories jars may come from
     * @param trustedSigners the certificates a jar's signers must be, or chain up to
     * @param classLoader    the node's class loader: class-path implementations, parent of jar loaders
     * @param contentsTypes  the node's registry, where a loaded class registers its contents
     */
    public ImplementationLoader(List<Path> allowlist, List<X509Certificate> trustedSigners, ClassLoader classLoader,
                                ContentsTypes contentsTypes) {
        this.allowlist = List.copyOf(allowlist);
        this.verifier = new PluginVerifier(trustedSigners);
        this.classLoader = Objects.requireNonNull(classLoader, "classLoader");
        this.contentsTypes = Objects.requireNonNull(contentsTypes, "contentsTypes");
    }

    /**
     * A loaded, checked implementation with its first instance already constructed.
     *
     * @param type    the class
     * @param source  {@link UpgradeResult#CLASSPATH} or the canonical path of the jar
     * @param loader  the jar's own class loader, or null for the class path
     * @param factory returns the first instance once, then constructs new ones (for restarts)
     */
    public record Loaded(Class<? extends Component> type, String source, URLClassLoader loader,
                         Supplier<Component> factory) {

        /** Closes the jar's class loader, if any; for an implementation that was never installed. */
        public void discard() {
            closeQuietly(loader);
        }
    }

    /**
     * Loads {@code className} from the class path ({@code jarPath} null) or from the jar.
     *
     * @throws LoadFailure naming what was wrong: the jar's place, the class, its contract, its
     *                     constructor
     */
    public Loaded load(String className, String jarPath, String configuration) throws LoadFailure {
        if (!BINARY_NAME.matcher(className).matches()) {
            throw new LoadFailure(Reason.BAD_REQUEST, "className='" + className
                    + "' is not a binary class name such as com.example.ControllerV2");
        }
        URLClassLoader jarLoader = null;
        try {
            String source = UpgradeResult.CLASSPATH;
            ClassLoader from = classLoader;
            if (jarPath != null) {
                Path jar = allowedJar(jarPath);
                source = jar.toString();
                Path verified = verifier.verifiedCopy(jar);
                try {
                    jarLoader = new JarClassLoader(verified, jar, classLoader);
                } catch (IOException | RuntimeException e) {
                    PluginVerifier.deleteQuietly(verified);
                    throw new LoadFailure(Reason.CLASS_NOT_LOADABLE, "jar '" + jar + "' cannot be opened: " + e, e);
                }
                from = jarLoader;
            }
            Class<? extends Component> type = checkedClass(className, from, jarLoader, source);
            registerContentsOf(type);
            Constructor<? extends Component> constructor = constructor(type, configuration);
            Object[] arguments = configuration == null ? new Object[0] : new Object[] {configuration};
            Component first = construct(constructor, arguments);
            var firstOnce = new AtomicReference<>(first);
            Supplier<Component> factory = () -> {
                Component unused = firstOnce.getAndSet(null);
                if (unused != null) {
                    return unused;
                }
                try {
                    return construct(constructor, arguments);
                } catch (LoadFailure e) {
                    throw new IllegalStateException(e.getMessage(), e.getCause());
                }
            };
            return new Loaded(type, source, jarLoader, factory);
        } catch (LoadFailure | RuntimeException | Error e) {
            closeQuietly(jarLoader);
            throw e;
        }
    }

    /**
     * Calls the class's {@code public static void registerContents(ContentsTypes)}, if it declares
     * one, on the node's registry: how an implementation from a jar, or the target of a migration,
     * brings its own contents (its state's type, new messages) before its first instance runs or
     * its state arrives. Explicit, and only for the class being loaded; never a static initializer.
     */
    private void registerContentsOf(Class<? extends Component> type) throws LoadFailure {
        Method register;
        try {
            register = type.getMethod("registerContents", ContentsTypes.class);
        } catch (NoSuchMethodException e) {
            return;
        }
        if (!Modifier.isStatic(register.getModifiers())) {
            throw new LoadFailure(Reason.INVALID_IMPLEMENTATION, "class '" + type.getName()
                    + "' declares registerContents(ContentsTypes) but not static; make it public static");
        }
        try {
            register.invoke(null, contentsTypes);
        } catch (InvocationTargetException e) {
            throw new LoadFailure(Reason.INVALID_IMPLEMENTATION, "class '" + type.getName()
                    + "'.registerContents failed: " + e.getCause(), e.getCause());
        } catch (IllegalAccessException e) {
            throw new LoadFailure(Reason.INVALID_IMPLEMENTATION, "class '" + type.getName()
                    + "'.registerContents is not accessible: " + e.getMessage(), e);
        }
    }

    /** The canonical jar, if it lies inside an allowlisted directory. */
    private Path allowedJar(String jarPath) throws LoadFailure {
        Path given;
        try {
            given = Path.of(jarPath).toAbsolutePath().normalize();
        } catch (InvalidPathException e) {
            throw new LoadFailure(Reason.BAD_REQUEST, "jarPath='" + jarPath + "' is not a valid path: " + e.getMessage());
        }
        Path real;
        try {
            real = given.toRealPath();
        } catch (NoSuchFileException e) {
            requireAllowed(jarPath, given);
            throw new LoadFailure(Reason.CLASS_NOT_LOADABLE, "jar '" + given + "' does not exist");
        } catch (IOException e) {
            requireAllowed(jarPath, given);
            throw new LoadFailure(Reason.CLASS_NOT_LOADABLE, "jar '" + given + "' cannot be resolved: " + e);
        }
        requireAllowed(jarPath, real);
        if (!Files.isRegularFile(real)) {
            throw new LoadFailure(Reason.CLASS_NOT_LOADABLE, "jar '" + real + "' is not a regular file");
        }
        return real;
    }

    private void requireAllowed(String jarPath, Path path) throws LoadFailure {
        for (Path directory : allowlist) {
            if (path.startsWith(directory)) {
                return;
            }
        }
        String resolved = path.toString().equals(jarPath) ? "" : " (resolved to '" + path + "')";
        throw new LoadFailure(Reason.CODE_NOT_ALLOWED, "jar '" + jarPath + "'" + resolved
                + (allowlist.isEmpty() ? " is refused: no directory is allowlisted for code on this node"
                        : " is outside the allowlisted directories " + allowlist)
                + "; allow its directory with ManagementConfig.builder().allowDirectory(...)");
    }

    private static Class<? extends Component> checkedClass(String className, ClassLoader from, URLClassLoader jar,
                                                           String source) throws LoadFailure {
        Class<?> type;
        try {
            // Not initialized yet: no code of the class runs before its contract is checked.
            type = Class.forName(className, false, from);
        } catch (ClassNotFoundException e) {
            throw new LoadFailure(Reason.CLASS_NOT_LOADABLE, "class '" + className + "' not found "
                    + (jar == null ? "on the class path" : "in jar '" + source + "' nor on the class path"));
        } catch (LinkageError e) {
            throw new LoadFailure(Reason.CLASS_NOT_LOADABLE, "class '" + className + "' from " + source
                    + " cannot be linked: " + e, e);
        }
        if (jar != null && type.getClassLoader() != jar) {
            throw new LoadFailure(Reason.CLASS_NOT_LOADABLE, "class '" + className + "' is not in jar '" + source
                    + "' (the node's own class is " + type.getName() + " from " + type.getClassLoader()
                    + "); request it without a jar, or put it in the jar");
        }
        if (!Component.class.isAssignableFrom(type)) {
            throw new LoadFailure(Reason.INVALID_IMPLEMENTATION, "class '" + className
                    + "' does not implement " + Component.class.getName());
        }
        int modifiers = type.getModifiers();
        if (type.isInterface() || Modifier.isAbstract(modifiers)) {
            throw new LoadFailure(Reason.INVALID_IMPLEMENTATION, "class '" + className
                    + "' is abstract; name a concrete class");
        }
        if (!Modifier.isPublic(modifiers) || (type.getEnclosingClass() != null && !Modifier.isStatic(modifiers))) {
            throw new LoadFailure(Reason.INVALID_IMPLEMENTATION, "class '" + className
                    + "' must be public and top level or static nested");
        }
        return type.asSubclass(Component.class);
    }

    private static Constructor<? extends Component> constructor(Class<? extends Component> type, String configuration)
            throws LoadFailure {
        try {
            return configuration == null ? type.getConstructor() : type.getConstructor(String.class);
        } catch (NoSuchMethodException e) {
            throw new LoadFailure(Reason.INVALID_IMPLEMENTATION, "class '" + type.getName() + "' has no public "
                    + (configuration == null ? "no-arg constructor (an upgrade without configuration needs one)"
                            : "constructor (String configuration) (an upgrade with configuration needs one)"));
        }
    }

    private static Component construct(Constructor<? extends Component> constructor, Object[] arguments)
            throws LoadFailure {
        String name = constructor.getDeclaringClass().getName();
        try {
            return constructor.newInstance(arguments);
        } catch (InvocationTargetException e) {
            throw new LoadFailure(Reason.CONSTRUCTION_FAILED, "the constructor of '" + name + "' threw "
                    + e.getCause(), e.getCause());
        } catch (ExceptionInInitializerError e) {
            throw new LoadFailure(Reason.CONSTRUCTION_FAILED, "the static initializer of '" + name + "' threw "
                    + e.getCause(), e.getCause());
        } catch (IllegalAccessException e) {
            throw new LoadFailure(Reason.INVALID_IMPLEMENTATION, "class '" + name + "' is not accessible (" + e.getMessage()
                    + "); export its package from its module");
        } catch (InstantiationException | LinkageError e) {
            throw new LoadFailure(Reason.CONSTRUCTION_FAILED, "class '" + name + "' cannot be instantiated: " + e, e);
        }
    }

    /** Closes a jar's class loader (null: nothing); a failure is logged. */
    public static void closeQuietly(URLClassLoader loader) {
        if (loader == null) {
            return;
        }
        try {
            loader.close();
        } catch (IOException e) {
            log.warn("closing the class loader {} failed; ignored", loader.getName(), e);
        }
    }
}
