package io.etherware.core.kernel;

import io.etherware.core.component.Shell;
import java.util.Objects;

/**
 * Where a registered profile lives: a component on this node or a route to another node.
 *
 * <p>Immutable.
 */
public sealed interface Endpoint {

    /** A component of this node. */
    record Local(Shell shell) implements Endpoint {
        public Local {
            Objects.requireNonNull(shell, "shell");
        }
    }

    /** A component of another node, reached through a transport. */
    record Remote(RemoteRoute route) implements Endpoint {
        public Remote {
            Objects.requireNonNull(route, "route");
        }
    }
}
