package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Profile;
import io.etherware.services.management.AccessRule.Operation;
import java.util.Set;
import org.junit.jupiter.api.Test;

/** The access list's matching rule, and its validation at build time. */
class AccessRuleTest {

    private static final Profile CONTROLLER = Profile.parse("controller[pendulum=1,site=lab]");

    private static boolean permits(String pattern, Profile profile) {
        return AccessRule.allow("ctl", Set.of(Operation.UPGRADE), pattern).permits("ctl", Operation.UPGRADE, profile);
    }

    @Test
    void shouldMatchTheRoleWithWildcardsAndRequireThePatternsAttributes() {
        assertTrue(permits("*", CONTROLLER));
        assertTrue(permits("controller", CONTROLLER), "a role alone matches any attributes");
        assertTrue(permits("controller*", CONTROLLER));
        assertTrue(permits("controller*", Profile.parse("controllerV2")));
        assertTrue(permits("*troll*", CONTROLLER));
        assertTrue(permits("controller[site=lab]", CONTROLLER), "a subset of the attributes, in any order");
        assertTrue(permits("controller[site=lab,pendulum=1]", CONTROLLER));
        assertFalse(permits("control", CONTROLLER), "no wildcard: the whole role");
        assertFalse(permits("controller[pendulum=2]", CONTROLLER));
        assertFalse(permits("controller[pendulum=1,car=1]", CONTROLLER), "every attribute of the pattern");
        assertFalse(permits("*[pendulum=2]", CONTROLLER));
        assertFalse(permits("dsp*", CONTROLLER));
    }

    @Test
    void shouldMatchTheNodeExactlyOrAnyNodeAndOnlyTheNamedOperations() {
        var rule = AccessRule.allow("ctl", Set.of(Operation.MIGRATE), "*");
        assertTrue(rule.permits("ctl", Operation.MIGRATE, CONTROLLER));
        assertFalse(rule.permits("ctl", Operation.UPGRADE, CONTROLLER));
        assertFalse(rule.permits("ctl2", Operation.MIGRATE, CONTROLLER));
        assertFalse(rule.permits("ct", Operation.MIGRATE, CONTROLLER));
        assertTrue(AccessRule.allow("*", Set.of(Operation.MIGRATE), "*").permits("anyone", Operation.MIGRATE, CONTROLLER));
    }

    @Test
    void shouldRefuseABadRuleNamingTheFieldAndTheValue() {
        var node = assertThrows(IllegalArgumentException.class,
                () -> AccessRule.allow("ctl*", Set.of(Operation.UPGRADE), "*"));
        assertTrue(node.getMessage().startsWith("node='ctl*'"), node.getMessage());
        var operations = assertThrows(IllegalArgumentException.class, () -> AccessRule.allow("ctl", Set.of(), "*"));
        assertTrue(operations.getMessage().startsWith("operations=[]"), operations.getMessage());
        for (String bad : new String[] {"", "[pendulum=1]", "controller[pendulum]", "con troller", "controller["}) {
            var pattern = assertThrows(IllegalArgumentException.class,
                    () -> AccessRule.allow("ctl", Set.of(Operation.UPGRADE), bad), bad);
            assertTrue(pattern.getMessage().startsWith("profilePattern='" + bad + "'"), pattern.getMessage());
        }
        assertEquals(1, ManagementConfig.builder().allowRemote("ctl", Set.of(Operation.UPGRADE), "controller").build()
                .accessList().size());
    }
}
