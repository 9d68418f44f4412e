package io.etherware.services.management;

import io.etherware.core.message.Profile;
import java.util.Arrays;
import java.util.EnumSet;
import java.util.Map;
import java.util.Objects;
import java.util.Set;
import java.util.regex.Pattern;
import java.util.stream.Collectors;

/**
 * One entry of a node's management access list ({@link ManagementConfig.Builder#allowRemote}):
 * which other node may ask for which {@link Operation operations} on which of this node's
 * components. A node without any rule refuses all management from other nodes.
 *
 * <h2>Matching</h2>
 * A rule permits a request when all three match:
 * <ul>
 *   <li>{@code node}: the id of the node the request came from, as the network layer established
 *       it from the connection ({@link io.etherware.core.message.Origin#nodeId()}), never from text
 *       in the message; {@code "*"} matches every node;</li>
 *   <li>{@code operations}: the operation asked for is one of them;</li>
 *   <li>{@code profilePattern}: the profile of the component the request is about. The pattern is
 *       a profile query whose role may contain {@code *} wildcards (each matches any run of name
 *       characters): a profile matches when its role matches the role pattern and it carries every
 *       attribute of the pattern with the same value (it may carry more). {@code "*"} matches every
 *       profile, {@code "controller"} every profile with the role {@code controller},
 *       {@code "controller*"} also {@code controllerV2[...]}, and {@code "controller[pendulum=1]"}
 *       only controllers of pendulum 1.</li>
 * </ul>
 * The profile matched is the exact profile of the local component the request reaches (a request
 * may name it by a query); a request that reaches no local component is matched by the profile it
 * names, and then fails for that reason if it is permitted.
 *
 * <p>Immutable; safe to share between threads.
 *
 * @param node           a node id, or {@code "*"} for every node
 * @param operations     what that node may ask for; not empty
 * @param profilePattern which components, see above
 */
public record AccessRule(String node, Set<Operation> operations, String profilePattern) {

    /** Any node. */
    public static final String ANY_NODE = "*";
    /** Any profile. */
    public static final String ANY_PROFILE = "*";

    private static final Pattern NAME = Pattern.compile(Profile.NAME_PATTERN);
    private static final String NAME_CHARS = "[A-Za-z0-9_.-]*";

    /** What a remote node may ask a management service for. */
    public enum Operation {
        /** Replace a component's logic ({@link UpgradeRequest}). */
        UPGRADE,
        /**
         * Move a component: ask this node to move one of its components away
         * ({@link MigrateRequest}), and move a component into this node (the source's
         * {@link MigrationStep}s, which a migration's source sends to its target).
         */
        MIGRATE
    }

    /**
     * Checks the rule and keeps an immutable copy of {@code operations}.
     *
     * @throws NullPointerException     if a field is null
     * @throws IllegalArgumentException if {@code node} is neither a node id nor {@code "*"},
     *                                  {@code operations} is empty, or {@code profilePattern} is
     *                                  not a pattern as described above
     */
    public AccessRule {
        Objects.requireNonNull(node, "node");
        Objects.requireNonNull(operations, "operations");
        Objects.requireNonNull(profilePattern, "profilePattern");
        if (!node.equals(ANY_NODE) && !NAME.matcher(node).matches()) {
            throw new IllegalArgumentException("node='" + node + "' must be a node id (" + Profile.NAME_PATTERN
                    + ") or \"*\" for any node");
        }
        if (operations.isEmpty()) {
            throw new IllegalArgumentException("operations=[] for node '" + node
                    + "': name at least one of " + EnumSet.allOf(Operation.class));
        }
        operations = Set.copyOf(EnumSet.copyOf(operations));
        compile(profilePattern); // validates
    }

    /**
     * A rule: {@code node} may ask for {@code operations} on the components {@code profilePattern}
     * matches.
     *
     * @param node           a node id, or {@link #ANY_NODE}
     * @param operations     what that node may ask for; not empty
     * @param profilePattern which components, or {@link #ANY_PROFILE}
     * @return the rule
     * @throws IllegalArgumentException if a field is not valid (see the constructor)
     */
    public static AccessRule allow(String node, Set<Operation> operations, String profilePattern) {
        return new AccessRule(node, operations, profilePattern);
    }

    /**
     * Whether this rule lets {@code nodeId} ask for {@code operation} on the component {@code profile}.
     * Parses the pattern on each call: management requests are rare and off the hot paths.
     *
     * @param nodeId    the node the request came from, as its connection established it
     * @param operation what it asks for
     * @param profile   the exact profile of the local component concerned (or, if none is reached,
     *                  the profile the request names)
     * @return true if all three match this rule
     */
    public boolean permits(String nodeId, Operation operation, Profile profile) {
        return (node.equals(ANY_NODE) || node.equals(nodeId)) && operations.contains(operation)
                && compile(profilePattern).matches(profile);
    }

    @Override
    public String toString() {
        return "allowRemote(\"" + node + "\", " + operations + ", \"" + profilePattern + "\")";
    }

    /** A parsed profile pattern: a role regex plus the attributes a profile must carry. */
    private record Compiled(Pattern role, Map<String, String> attributes) {
        boolean matches(Profile profile) {
            if (!role.matcher(profile.role()).matches()) {
                return false;
            }
            for (var attribute : attributes.entrySet()) {
                if (!attribute.getValue().equals(profile.attributes().get(attribute.getKey()))) {
                    return false;
                }
            }
            return true;
        }
    }

    private static Compiled compile(String pattern) {
        if (pattern.equals(ANY_PROFILE)) {
            return new Compiled(Pattern.compile(".*"), Map.of());
        }
        int bracket = pattern.indexOf('[');
        String rolePattern = bracket < 0 ? pattern : pattern.substring(0, bracket);
        if (rolePattern.isEmpty() || !NAME.matcher(rolePattern.replace('*', 'x')).matches()) {
            throw new IllegalArgumentException("profilePattern='" + pattern + "': the role part '" + rolePattern
                    + "' must be a role (" + Profile.NAME_PATTERN + ") in which * matches any run of characters,"
                    + " e.g. \"controller*\" or \"controller[pendulum=1]\"; \"*\" matches every profile");
        }
        Map<String, String> attributes = Map.of();
        if (bracket >= 0) {
            try {
                attributes = Profile.parse("pattern" + pattern.substring(bracket)).attributes();
            } catch (IllegalArgumentException e) {
                throw new IllegalArgumentException("profilePattern='" + pattern + "': the attributes part is not"
                        + " [key=value,...]: " + e.getMessage(), e);
            }
        }
        // Each * matches any run of name characters; the rest is literal.
        String role = Arrays.stream(rolePattern.split("\\*", -1)).map(Pattern::quote)
                .collect(Collectors.joining(NAME_CHARS));
        return new Compiled(Pattern.compile(role), attributes);
    }
}
