package io.etherware.examples.scenario;

import io.etherware.pendulum.components.ControlListener;
import java.util.Objects;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ConcurrentMap;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Where a controller loaded at runtime (from a plugin jar, by the management service) finds the
 * scenario's {@link ControlListener}: a plugin is constructed from a class name and a
 * configuration string, so it names the listener and looks it up here. This class is on the
 * node's class path and never in a plugin jar, so the node and every plugin share its one map.
 *
 * <p>Thread-safe.
 */
public final class ControlListeners {

    private static final Logger LOG = LoggerFactory.getLogger(ControlListeners.class);
    private static final ConcurrentMap<String, ControlListener> LISTENERS = new ConcurrentHashMap<>();

    private ControlListeners() {
    }

    /**
     * Makes {@code listener} known as {@code name} until the returned handle is closed.
     *
     * @throws IllegalStateException if the name is taken
     */
    public static Registration register(String name, ControlListener listener) {
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(listener, "listener");
        if (LISTENERS.putIfAbsent(name, listener) != null) {
            throw new IllegalStateException("a control listener named '" + name + "' is already registered");
        }
        return () -> LISTENERS.remove(name, listener);
    }

    /** The listener registered as {@code name}, or {@link ControlListener#NONE} (with a warning). */
    public static ControlListener named(String name) {
        ControlListener listener = name == null ? null : LISTENERS.get(name);
        if (listener == null) {
            LOG.warn("no control listener named '{}'; the controller's cycles go unrecorded", name);
            return ControlListener.NONE;
        }
        return listener;
    }

    /** A registration; closing it forgets the listener. */
    @FunctionalInterface
    public interface Registration extends AutoCloseable {
        @Override
        void close();
    }
}
