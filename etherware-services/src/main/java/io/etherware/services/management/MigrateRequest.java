package io.etherware.services.management;

import io.etherware.core.message.Contents;
import io.etherware.core.message.Profile;
import java.util.Objects;

/**
 * A management request to move a running component to another node (paper Section VI-C2),
 * registered as {@code etherware.migrate}. Send it to the management service of the node that
 * hosts the component, {@link Management#profileOf(String)}, as a request; it is answered with a
 * {@link MigrationResult} or a {@link ManagementFailure}. {@link Management#migrate} does that.
 *
 * <p>Immutable; safe to share between threads.
 *
 * @param target        the component's profile on the source node (exact, or a query matching one)
 * @param toNode        the id of the node to move it to; it must be connected to the source
 *                      through the source's NetworkMessenger, and its access list must let the
 *                      source {@link AccessRule.Operation#MIGRATE MIGRATE} the component
 * @param className     the class the target instantiates, or null for the class of the logic
 *                      running now; see {@link Implementation} for the class's contract
 * @param jarPath       a jar inside one of the target's allowlisted directories, signed by a key
 *                      the target trusts, or null to load the class from the target's class path
 * @param configuration the argument of the class's {@code (String)} constructor, or null for its
 *                      no-arg constructor
 */
public record MigrateRequest(Profile target, String toNode, String className, String jarPath, String configuration)
        implements Contents {

    /**
     * Checks that the target and the destination are given; the rest is checked by the nodes.
     *
     * @throws NullPointerException if {@code target} or {@code toNode} is null
     */
    public MigrateRequest {
        Objects.requireNonNull(target, "target");
        Objects.requireNonNull(toNode, "toNode");
    }

    /**
     * Moves {@code target} to {@code toNode} as an instance of the class it runs now (no-arg
     * constructor), loaded from the destination's class path.
     *
     * @param target the component's profile on the source node, exact or a query matching one
     * @param toNode the id of the node to move it to
     * @return the request
     */
    public static MigrateRequest of(Profile target, String toNode) {
        return new MigrateRequest(target, toNode, null, null, null);
    }

    /**
     * Moves {@code target} to {@code toNode} as an instance of {@code implementation}.
     *
     * @param target         the component's profile on the source node, exact or a query matching
     *                       one
     * @param toNode         the id of the node to move it to
     * @param implementation the class to instantiate there, with its jar and configuration
     * @return the request
     */
    public static MigrateRequest of(Profile target, String toNode, Implementation implementation) {
        return new MigrateRequest(target, toNode, implementation.className(),
                implementation.jar() == null ? null : implementation.jar().toString(), implementation.configuration());
    }
}
