package io.etherware.deploy;

import io.etherware.core.component.Component;
import io.etherware.core.message.ContentsTypes;
import io.etherware.deploy.view.LiveSignals;
import java.util.function.Supplier;

/**
 * Makes a component of a deployment from its {@code <setting>}s: what a {@code <component
 * class="...">} names when the component needs configuration or resources (a serial port, a
 * file). The launcher makes one instance per {@code <component>} element through the public
 * no-argument constructor, calls {@link #registerContents} while it builds the node, then
 * {@link #create} once, before the node starts; the supplier it returns makes the first instance
 * and every one that supervision or an upgrade's rollback starts later.
 *
 * <p>Every setting the file gives must be read by {@code create} (through {@link Settings}): one
 * that is not is reported as a mistake, naming its line, so a misspelt name does not pass
 * silently as its default.
 */
public interface ComponentFactory {

    /**
     * Registers the contents types the component sends and receives, in the node's registry.
     * Default: none.
     *
     * @param types the node's contents types
     */
    default void registerContents(ContentsTypes types) {
    }

    /**
     * Reads the settings, opens what the component needs, and returns its factory.
     *
     * @param settings  the element's settings; throws {@link DeploymentException} naming the
     *                  setting's line for a missing or bad one
     * @param resources where to hand what must be closed after the node has closed (a port, a
     *                  simulated plant)
     * @return the component's factory, called on the node's threads
     * @throws DeploymentException for a bad setting, or a resource that cannot be opened (name it
     *                             and the setting that chose it)
     */
    Supplier<? extends Component> create(Settings settings, Resources resources) throws DeploymentException;

    /**
     * What the node gives a {@link ComponentFactory}: a place for what must be closed after it,
     * and its live signals.
     */
    interface Resources {

        /**
         * Closes {@code resource} after the node, its network and its Notifier have closed, in the
         * reverse order of the calls; also if the deployment fails to start after this call.
         *
         * @param resource what to close
         * @param <T>      its type
         * @return {@code resource}, for chaining
         */
        <T extends AutoCloseable> T closeAfterNode(T resource);

        /**
         * The node's live signals, for the component to publish measurements into (a controller's
         * angles and torque): create each signal here, in {@code create}, and record into it from
         * the component. Its {@code <view>}, if the file has one, plots them and exports their
         * newest values; without a view they are kept and not shown.
         *
         * @return the node's signals, shared by all its factories (signal names are unique per node)
         */
        LiveSignals signals();
    }
}
