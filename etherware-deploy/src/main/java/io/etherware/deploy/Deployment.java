package io.etherware.deploy;

import io.etherware.core.message.Profile;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.deploy.view.ViewConfig;
import io.etherware.services.management.ManagementConfig;
import io.etherware.services.network.NetworkConfig;
import io.etherware.services.notifier.NotifierConfig;
import io.etherware.services.notifier.Subscription;
import java.nio.file.Path;
import java.util.List;
import java.util.Objects;
import java.util.Optional;
import java.util.function.Supplier;

/**
 * One node's deployment, read and checked by {@link DeploymentReader}: every configuration built
 * and validated, every class loaded, every file it names read; what is left for
 * {@link DeployedNode#start} is to open the components' resources and start. Immutable apart from
 * the components' {@link Settings}, which the launcher reads once.
 *
 * @param file       the file it was read from
 * @param nodeId     the node's id
 * @param scheduler  the node's scheduler
 * @param notifier   the Notifier and its subscriptions, if the file has a {@code <notifier>}
 * @param components the components, in file order
 * @param network    the network configuration, if the file has a {@code <network>}
 * @param management the management service's configuration, if the file has a {@code <management>}
 * @param view       the live view, if the file has a {@code <view>}
 */
public record Deployment(Path file, String nodeId, SchedulerPlan scheduler, Optional<NotifierPlan> notifier,
                         List<ComponentPlan> components, Optional<NetworkConfig> network,
                         Optional<ManagementConfig> management, Optional<ViewPlan> view) {

    /** Checks that nothing is null and copies the list. */
    public Deployment {
        Objects.requireNonNull(file, "file");
        Objects.requireNonNull(nodeId, "nodeId");
        Objects.requireNonNull(scheduler, "scheduler");
        Objects.requireNonNull(notifier, "notifier");
        components = List.copyOf(components);
        Objects.requireNonNull(network, "network");
        Objects.requireNonNull(management, "management");
        Objects.requireNonNull(view, "view");
    }

    /**
     * A deployment without a live view.
     *
     * @param file       the file it was read from
     * @param nodeId     the node's id
     * @param scheduler  the node's scheduler
     * @param notifier   the Notifier and its subscriptions, if any
     * @param components the components, in file order
     * @param network    the network configuration, if any
     * @param management the management service's configuration, if any
     */
    public Deployment(Path file, String nodeId, SchedulerPlan scheduler, Optional<NotifierPlan> notifier,
            List<ComponentPlan> components, Optional<NetworkConfig> network, Optional<ManagementConfig> management) {
        this(file, nodeId, scheduler, notifier, components, network, management, Optional.empty());
    }

    /**
     * The node's scheduler.
     *
     * @param type        {@code realtime} or {@code fifo}, as written
     * @param factory     makes it when the node is built
     * @param description one line for the log: the type and its dispatchers
     */
    public record SchedulerPlan(String type, Supplier<? extends Scheduler> factory, String description) {
    }

    /**
     * The Notifier.
     *
     * @param config        its thread and profile
     * @param subscriptions started each when its target resolves
     */
    public record NotifierPlan(NotifierConfig config, List<Subscription> subscriptions) {

        /** Checks the config and copies the list. */
        public NotifierPlan {
            Objects.requireNonNull(config, "config");
            subscriptions = List.copyOf(subscriptions);
        }
    }

    /**
     * One {@code <component>}.
     *
     * @param profile   where it is added
     * @param className the class the file names
     * @param factory   makes it
     * @param settings  its settings, for {@link ComponentFactory#create}
     * @param line      the element's line, for errors found at start
     */
    public record ComponentPlan(Profile profile, String className, ComponentFactory factory, Settings settings,
                                int line) {
    }

    /**
     * The {@code <view>}: the node's page and metrics endpoint.
     *
     * @param config where it listens
     * @param line   the element's line, for errors found at start (the port is taken)
     */
    public record ViewPlan(ViewConfig config, int line) {

        /** Checks the config. */
        public ViewPlan {
            Objects.requireNonNull(config, "config");
        }
    }
}
