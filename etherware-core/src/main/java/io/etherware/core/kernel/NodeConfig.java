package io.etherware.core.kernel;

import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Profile;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import java.time.Duration;
import java.util.Objects;
import java.util.function.Supplier;

/**
 * The configuration of an {@link EtherwareNode}, validated once when it is built. Every field has
 * a default that works on a laptop without privileges; they are all listed in {@link Builder}.
 *
 * <p>Immutable. The scheduler is given as a factory because a scheduler runs one node once.
 *
 * @param nodeId                  this node's id: part of every message id, unique in the system
 * @param scheduler               makes the node's scheduler
 * @param clock                   the node's clock
 * @param supervision             the restart policy of components added without their own
 * @param escalation              what the node does when a component exceeds its restart intensity
 * @param defaultRequestTimeoutNs timeout of requests made without one; &gt; 0
 * @param drainTimeoutNs          how long {@code close()} lets queued messages be delivered before
 *                                it discards (and counts) the rest; &gt;= 0
 * @param contentsTypes           the node's registry of contents types: what its codecs (the
 *                                network's, state snapshots) carry. The node adds the kernel's own
 *                                notices, services add theirs when installed, the code that builds
 *                                the node adds the application's. Thread-safe; it only grows
 */
public record NodeConfig(String nodeId, Supplier<? extends Scheduler> scheduler, NodeClock clock,
                         SupervisionPolicy supervision, Escalation escalation, long defaultRequestTimeoutNs,
                         long drainTimeoutNs, ContentsTypes contentsTypes) {

    /**
     * Validates the configuration.
     *
     * @throws IllegalArgumentException naming the field, its value and a fix if {@code nodeId} is
     *                                  missing or malformed, or a timeout is out of range
     * @throws NullPointerException     naming the field and a fix if the scheduler factory, clock,
     *                                  supervision or escalation is null
     */
    public NodeConfig {
        if (nodeId == null || !Profile.isName(nodeId)) {
            throw new IllegalArgumentException("nodeId=" + (nodeId == null ? "null" : "'" + nodeId + "'")
                    + " must match " + Profile.NAME_PATTERN + ", e.g. nodeId(\"plant-1\")");
        }
        Objects.requireNonNull(scheduler, "scheduler=null: give a factory, e.g. scheduler(FifoScheduler::new)");
        Objects.requireNonNull(clock, "clock=null: use NodeClock.system() or leave the default");
        Objects.requireNonNull(supervision, "supervision=null: use SupervisionPolicy.DEFAULT or leave the default");
        Objects.requireNonNull(escalation, "escalation=null: use Escalation.RESET_ALL or STOP_NODE");
        if (defaultRequestTimeoutNs <= 0) {
            throw new IllegalArgumentException("defaultRequestTimeoutNs=" + defaultRequestTimeoutNs
                    + " must be > 0, e.g. defaultRequestTimeout(Duration.ofSeconds(1))");
        }
        if (drainTimeoutNs < 0) {
            throw new IllegalArgumentException("drainTimeoutNs=" + drainTimeoutNs
                    + " must be >= 0 (0 discards whatever is queued at close)");
        }
        Objects.requireNonNull(contentsTypes, "contentsTypes=null: leave the default (a new registry) or give one");
    }

    /** {@return a builder holding the defaults} */
    public static Builder builder() {
        return new Builder();
    }

    /**
     * Builds a {@link NodeConfig}. Defaults: node id {@code node}, {@link FifoScheduler}, the
     * system clock, {@link SupervisionPolicy#DEFAULT}, {@link Escalation#RESET_ALL}, request
     * timeout 1 s, drain timeout 1 s, a new {@link ContentsTypes} (the built-in types; the node adds
     * its own). Not thread-safe; use it on one thread.
     */
    public static final class Builder {
        private String nodeId = "node";
        private Supplier<? extends Scheduler> scheduler = FifoScheduler::new;
        private NodeClock clock = NodeClock.system();
        private SupervisionPolicy supervision = SupervisionPolicy.DEFAULT;
        private Escalation escalation = Escalation.RESET_ALL;
        private long defaultRequestTimeoutNs = Duration.ofSeconds(1).toNanos();
        private long drainTimeoutNs = Duration.ofSeconds(1).toNanos();
        private ContentsTypes contentsTypes;

        Builder() {
        }

        /**
         * This node's id; default {@code node}.
         *
         * @param value an id unique in the system that matches {@link Profile#NAME_PATTERN}
         *              (checked by {@link #build()})
         * @return this builder
         */
        public Builder nodeId(String value) {
            nodeId = value;
            return this;
        }

        /**
         * The factory of the node's scheduler; default {@code FifoScheduler::new}.
         *
         * @param value makes a new, unstarted scheduler each time a node is created from the
         *              configuration
         * @return this builder
         */
        public Builder scheduler(Supplier<? extends Scheduler> value) {
            scheduler = value;
            return this;
        }

        /**
         * The node's clock; default {@link NodeClock#system()}. Tests inject a manual one.
         *
         * @param value the clock of message time stamps and dispatching
         * @return this builder
         */
        public Builder clock(NodeClock value) {
            clock = value;
            return this;
        }

        /**
         * The restart policy of components added without their own; default
         * {@link SupervisionPolicy#DEFAULT}.
         *
         * @param value the policy
         * @return this builder
         */
        public Builder supervision(SupervisionPolicy value) {
            supervision = value;
            return this;
        }

        /**
         * What the node does when a component exceeds its restart intensity; default
         * {@link Escalation#RESET_ALL}.
         *
         * @param value the node's answer
         * @return this builder
         */
        public Builder escalation(Escalation value) {
            escalation = value;
            return this;
        }

        /**
         * Timeout of requests made without one; default 1 s.
         *
         * @param value positive (checked by {@link #build()})
         * @return this builder
         * @throws IllegalArgumentException if it is too long to count in nanoseconds
         */
        public Builder defaultRequestTimeout(Duration value) {
            defaultRequestTimeoutNs = SupervisionPolicy.toNs("defaultRequestTimeout", value);
            return this;
        }

        /**
         * How long {@code close()} lets queued messages be delivered before it discards (and
         * counts) the rest; default 1 s.
         *
         * @param value zero or positive (checked by {@link #build()}); zero discards at once
         * @return this builder
         * @throws IllegalArgumentException if it is too long to count in nanoseconds
         */
        public Builder drainTimeout(Duration value) {
            drainTimeoutNs = SupervisionPolicy.toNs("drainTimeout", value);
            return this;
        }

        /**
         * The node's contents types, with the application's registered, e.g.
         * {@code contentsTypes(new ContentsTypes().register("reading", Reading.class))}; default a new
         * registry. A registry may be shared by the nodes of one process that carry the same types.
         *
         * @param value the registry, not null
         * @return this builder
         * @throws NullPointerException if {@code value} is null
         */
        public Builder contentsTypes(ContentsTypes value) {
            contentsTypes = Objects.requireNonNull(value, "contentsTypes=null: leave the default or give a registry");
            return this;
        }

        /**
         * Validates the settings.
         *
         * @return the configuration
         * @throws IllegalArgumentException naming the setting, its value and a fix if one is out of
         *                                  range
         * @throws NullPointerException     naming the setting if a required one was set to null
         */
        public NodeConfig build() {
            return new NodeConfig(nodeId, scheduler, clock, supervision, escalation, defaultRequestTimeoutNs,
                    drainTimeoutNs, contentsTypes != null ? contentsTypes : new ContentsTypes());
        }
    }
}
