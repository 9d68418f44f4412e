package io.etherware.services.management.internal;

import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.message.Message;
import io.etherware.core.message.Origin;
import io.etherware.core.message.Profile;
import io.etherware.services.management.AccessRule;
import io.etherware.services.management.AccessRule.Operation;
import io.etherware.services.management.ManagementConfig;
import io.etherware.services.management.MigrationStep;
import java.util.List;
import java.util.Locale;
import java.util.Objects;
import java.util.concurrent.atomic.AtomicBoolean;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Decides whether a management request, a migration step or a migration step's answer may be
 * acted on, from where it came as the network layer established it ({@link Message#origin()}),
 * never from text a peer wrote; the rule is on {@link ManagementConfig}. Answers with the text of
 * the refusal (what was refused, and the fix) or null.
 *
 * <p>Thread-safety: immutable apart from a warn-once flag; any thread. Resolves profiles in the
 * node's registry (lock-free reads), so it may run on a dispatcher.
 */
public final class AccessControl {

    private static final Logger log = LoggerFactory.getLogger(AccessControl.class);

    private final Kernel kernel;
    private final List<AccessRule> accessList;
    private final boolean allowUnauthenticatedLinks;
    private final AtomicBoolean warnedNoOrigin = new AtomicBoolean();

    public AccessControl(Kernel kernel, ManagementConfig config) {
        this.kernel = Objects.requireNonNull(kernel, "kernel");
        this.accessList = config.accessList();
        this.allowUnauthenticatedLinks = config.allowUnauthenticatedLinks();
    }

    /**
     * Why {@code message}, asking for {@code operation} (called {@code operationName} in answers)
     * on the component {@code target} names, must be refused; null if it may be served.
     */
    public String refusal(Message message, Operation operation, String operationName, Profile target) {
        Origin origin = message.origin();
        if (origin == null) {
            noticeLocalWithForeignId(message);
            return null;
        }
        String what = "request " + message.messageId() + " to " + operationName + " '" + target + "'";
        String linkRefusal = linkRefusal(origin, what);
        if (linkRefusal != null) {
            return linkRefusal;
        }
        Profile component = componentOf(target);
        for (AccessRule rule : accessList) {
            if (rule.permits(origin.nodeId(), operation, component)) {
                return null;
            }
        }
        String verb = operation.name().toLowerCase(Locale.ROOT);
        return "node '" + origin.nodeId() + "' may not " + verb + " '" + component + "' on node '" + kernel.nodeId()
                + "'" + (operationName.equals(verb) ? "" : " (" + operationName + ")") + ": " + (accessList.isEmpty()
                        ? "the access list is empty, so this node refuses all management from other nodes"
                        : "no rule of the access list " + accessList + " permits it")
                + "; allow it with ManagementConfig.builder().allowRemote(\"" + origin.nodeId() + "\", Set.of(Operation."
                + operation + "), \"" + component + "\")";
    }

    /**
     * Why a migration step must be refused, beyond {@link #refusal}: its {@code fromNode} must
     * name the node it came from. Null if it may be served.
     */
    public String stepRefusal(Message message, MigrationStep step) {
        Origin origin = message.origin();
        if (origin != null && !origin.nodeId().equals(step.fromNode())) {
            return "the " + step.phase() + " step of '" + step.target() + "' says it comes from node '"
                    + step.fromNode() + "' but arrived from node '" + origin.nodeId() + "'";
        }
        return null;
    }

    /**
     * Why the answer {@code reply} to a step sent to {@code toNode} must not be taken; null if it
     * may. An answer from the network must come straight from the target over a link that
     * authenticated it (or an unauthenticated one, if allowed). An answer made on this node (no
     * origin) is this node's own code, which is trusted like every local component.
     */
    public String answerRefusal(Message reply, String toNode, MigrationStep step) {
        Origin origin = reply.origin();
        if (origin == null) {
            return null;
        }
        String what = "the answer to the " + step.phase() + " step of '" + step.target() + "'";
        if (!origin.nodeId().equals(toNode)) {
            return what + " came from node '" + origin.nodeId() + "', not from the target node '" + toNode
                    + "'; only the target answers its steps";
        }
        return linkRefusal(origin, what);
    }

    /** Refuses what came through a relay, or over an unauthenticated link unless allowed. */
    private String linkRefusal(Origin origin, String what) {
        if (!origin.isDirect()) {
            return what + " was made on node '" + origin.nodeId() + "' and relayed to node '" + kernel.nodeId()
                    + "' by node '" + origin.viaNodeId() + "' (" + origin.hops() + " relay(s)); node '"
                    + kernel.nodeId() + "' takes management only straight from the node that asks, because a relay"
                    + " must not lend its rights: send it over a direct connection";
        }
        if (!origin.authenticated() && !allowUnauthenticatedLinks) {
            return what + " came from node '" + origin.nodeId() + "' over a link that did not authenticate it"
                    + " (plain TCP), so that node id is only the peer's word; connect the nodes with TLS, or, for"
                    + " loopback development only, ManagementConfig.builder().allowUnauthenticatedLinks(true)";
        }
        return null;
    }

    /** The exact profile of the local component {@code named} reaches, or {@code named} if none. */
    private Profile componentOf(Profile named) {
        try {
            if (kernel.registry().resolve(named) instanceof Endpoint.Local local) {
                return local.shell().profile();
            }
        } catch (ProfileResolutionException e) {
            // reaches no component here: matched as named, and then answered UNKNOWN_COMPONENT
        }
        return named;
    }

    /**
     * A request without an origin was made on this node and is served. One whose id names another
     * node is a sign that a network layer delivered it without setting its origin: said once.
     */
    private void noticeLocalWithForeignId(Message message) {
        String idNode = message.messageId().nodeId();
        if (!idNode.equals(kernel.nodeId()) && warnedNoOrigin.compareAndSet(false, true)) {
            log.warn("node {}: management request {} has no origin, so it is served as made on this node, but its id"
                    + " names node '{}': if it came from the network, the network layer does not set"
                    + " Message.origin and other nodes are not told apart from this one (said once)", kernel.nodeId(),
                    message.messageId(), idNode);
        }
    }
}
