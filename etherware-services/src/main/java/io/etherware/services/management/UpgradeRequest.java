package io.etherware.services.management;

import io.etherware.core.message.Contents;
import io.etherware.core.message.Profile;
import java.util.Objects;

/**
 * A management request to replace a component's logic at run time (paper Section VI-C1),
 * registered as {@code etherware.upgrade}. Send it to the management service of the component's
 * node, {@link Management#profileOf(String)}, as a request (it is answered with an
 * {@link UpgradeResult} or a {@link ManagementFailure}); {@link Management#upgrade} does that.
 *
 * <p>Immutable; safe to share between threads.
 *
 * @param target        the component's profile on that node (exact, or a query matching one)
 * @param className     the binary name of the new logic's class, e.g. {@code com.example.ControllerV2};
 *                      see {@link Implementation} for the class's contract
 * @param jarPath       a jar inside one of the node's allowlisted directories, signed by a key the
 *                      node trusts, to load the class from, through a class loader of its own;
 *                      null to load it from the node's class path
 * @param configuration handed to the class's {@code (String)} constructor; null to use its no-arg
 *                      constructor
 */
public record UpgradeRequest(Profile target, String className, String jarPath, String configuration)
        implements Contents {

    /**
     * Checks that the target and the class are given; the rest is checked by the managed node.
     *
     * @throws NullPointerException if {@code target} or {@code className} is null
     */
    public UpgradeRequest {
        Objects.requireNonNull(target, "target");
        Objects.requireNonNull(className, "className");
    }

    /**
     * The request for {@code implementation}.
     *
     * @param target         the component's profile on the managed node, exact or a query
     *                       matching one
     * @param implementation the new logic: its class, jar and configuration
     * @return the request
     */
    public static UpgradeRequest of(Profile target, Implementation implementation) {
        return new UpgradeRequest(target, implementation.className(),
                implementation.jar() == null ? null : implementation.jar().toString(), implementation.configuration());
    }
}
