package io.etherware.core.kernel;

import io.etherware.core.component.Shell;
import java.util.Objects;

/**
 * Where a registered profile lives: a component on this node or a route to another node.
 *
 * <p>Immutable.
 */
public sealed interface Endpoint {

    /**
     * A component of this node.
     *
     * @param shell the kernel's shell around the component
     */
    record Local(Shell shell) implements Endpoint {
        /**
         * Checks that there is a shell.
         *
         * @throws NullPointerException if {@code shell} is null
         */
        public Local {
            Objects.requireNonNull(shell, "shell");
        }
    }

    /**
     * A component of another node, reached through a transport.
     *
     * @param route the transport's way to the node that hosts it
     */
    record Remote(RemoteRoute route) implements Endpoint {
        /**
         * Checks that there is a route.
         *
         * @throws NullPointerException if {@code route} is null
         */
        public Remote {
            Objects.requireNonNull(route, "route");
        }
    }
}
