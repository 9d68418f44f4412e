package io.etherware.services.management.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Message;
import io.etherware.services.management.ManagementFailure;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * An implementation loaded for an upgrade or a migration brings its own contents types: the loader
 * calls its {@code public static registerContents(ContentsTypes)} on the node's registry.
 */
class ImplementationLoaderContentsTest {

    /** A state type only the implementation knows. */
    public record Gauge(double value) implements Contents {}

    /** Registers {@link Gauge} when loaded. */
    public static class Registering implements Component {
        public static void registerContents(ContentsTypes types) {
            types.register("test.gauge", Gauge.class);
        }

        @Override
        public void onMessage(Message message, ComponentContext context) {
        }
    }

    /** Declares the hook but not static: a mistake the loader names. */
    public static class NotStatic implements Component {
        public void registerContents(ContentsTypes types) {
        }

        @Override
        public void onMessage(Message message, ComponentContext context) {
        }
    }

    /** Declares no hook. */
    public static class Plain implements Component {
        @Override
        public void onMessage(Message message, ComponentContext context) {
        }
    }

    private final ContentsTypes nodeTypes = new ContentsTypes();
    private final ImplementationLoader loader = new ImplementationLoader(List.of(), List.of(),
            ImplementationLoaderContentsTest.class.getClassLoader(), nodeTypes);

    @Test
    void shouldRegisterTheImplementationsContentsOnTheNodesRegistryWhenItLoads() throws Exception {
        assertNull(nodeTypes.typeOf("test.gauge"));

        loader.load(Registering.class.getName(), null, null);

        assertEquals(Gauge.class, nodeTypes.typeOf("test.gauge"));
    }

    @Test
    void shouldRefuseAnImplementationWhoseRegisterContentsIsNotStatic() {
        var failure = assertThrows(LoadFailure.class, () -> loader.load(NotStatic.class.getName(), null, null));

        assertEquals(ManagementFailure.Reason.INVALID_IMPLEMENTATION, failure.reason());
        assertTrue(failure.getMessage().contains("make it public static"), failure.getMessage());
    }

    @Test
    void shouldLoadAnImplementationWithoutTheHookAndRegisterNothing() throws Exception {
        loader.load(Plain.class.getName(), null, null);

        assertEquals(new ContentsTypes().names(), nodeTypes.names());
    }
}
