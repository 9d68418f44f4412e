package io.etherware.services.management;

import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.Shell;
import io.etherware.core.kernel.ComponentHost;
import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.services.management.AccessRule.Operation;
import io.etherware.services.management.ManagementFailure.Reason;
import io.etherware.services.management.internal.AccessControl;
import io.etherware.services.management.internal.LoadFailure;
import org.slf4j.Logger;

/**
 * What the parts of a running management service ({@link Upgrades}, {@link Migrations}) share,
 * made when it starts, and the checks and answers every request goes through: the access check on
 * arrival, finding the local component a request names, and replying.
 *
 * <p>Immutable; its parts are thread-safe. Used on the service's dispatcher and its two threads;
 * takes no lock.
 *
 * @param kernel     the node whose components the service manages
 * @param config     the service's configuration
 * @param context    the service's own component context: its profile, replies and sends
 * @param log        the service's logger
 * @param counters   the counters shared by the service's restarts
 * @param access     decides whether a request from another node may be served
 * @param jarLoaders the jar loaders behind the node's components, shared by the service's restarts
 */
record ManagementContext(ComponentHost kernel, ManagementConfig config, ComponentContext context, Logger log,
                         ManagementCounters counters, AccessControl access, JarLoaders jarLoaders) {

    /**
     * Refuses (counts, logs and answers) a request that arrived from another node unless the
     * access list lets that node ask for {@code operation} on {@code target}; see
     * {@link ManagementConfig} for the rule.
     */
    boolean refused(Message message, Operation operation, String operationName, Profile target) {
        String refusal = access.refusal(message, operation, operationName, target);
        if (refusal == null && message.contents() instanceof MigrationStep step) {
            refusal = access.stepRefusal(message, step);
        }
        if (refusal == null) {
            return false;
        }
        counters.refused.increment();
        log.warn("refused {} request {} of '{}' from node '{}' (sender '{}'): {}", operationName, message.messageId(),
                target, message.origin().nodeId(), message.sender(), refusal);
        reply(message, new ManagementFailure(operationName, target, Reason.REMOTE_REFUSED, refusal));
        return true;
    }

    /** The running component of this node at {@code target}, other than the service itself. */
    Shell localShell(Profile target) throws LoadFailure {
        Endpoint endpoint;
        try {
            endpoint = kernel.registry().resolve(target);
        } catch (ProfileResolutionException e) {
            throw new LoadFailure(Reason.UNKNOWN_COMPONENT, e.getMessage());
        }
        if (!(endpoint instanceof Endpoint.Local local)) {
            throw new LoadFailure(Reason.UNKNOWN_COMPONENT, "'" + target + "' is hosted on another node, not on '"
                    + kernel.nodeId() + "'; send the request to that node's management service");
        }
        Shell shell = local.shell();
        if (shell.profile().equals(context.self())) {
            throw new LoadFailure(Reason.BAD_REQUEST, "the management service cannot upgrade or migrate itself");
        }
        if (shell.state() != Shell.State.RUNNING) {
            throw new LoadFailure(Reason.NOT_RUNNING, "component '" + shell.profile() + "' is " + shell.state()
                    + "; only a RUNNING component can be upgraded or migrated");
        }
        return shell;
    }

    /** Answers {@code request} with {@code answer}, if it has a sender to answer. */
    void reply(Message request, Contents answer) {
        if (request.hasSender()) {
            context.reply(request, answer);
        }
    }
}
