package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Profile;
import io.etherware.services.management.AccessRule.Operation;
import java.nio.file.Path;
import java.util.Map;
import java.util.Set;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * The README's management example, verbatim between the markers, so that it always compiles and
 * runs: a node that loads plugins only from one directory and only when signed by a key of its
 * trust store (made here as the README's keytool recipe makes it), and that lets one other node
 * upgrade and migrate its controllers.
 */
class ReadmeManagementExampleIT {

    @TempDir
    Path plugins;
    @TempDir
    Path keys;

    @Test
    void shouldRunTheManagementReadmeExample() throws Exception {
        JarBuilder.SigningKey signer = JarBuilder.newKey(keys, "plugins", 0, 30);
        Path trustStore = JarBuilder.trustStore(keys.resolve("plugin-trust.p12"), signer);
        char[] password = JarBuilder.PASSWORD.toCharArray();
        JarBuilder.sign(JarBuilder.build(plugins.resolve("controller-v2.jar"), Map.of("com.example.ControllerV2", """
                package com.example;
                public class ControllerV2 implements io.etherware.core.component.Component {
                    @Override public void onMessage(io.etherware.core.message.Message message,
                            io.etherware.core.component.ComponentContext context) { }
                }
                """)), signer);
        try (var node = EtherwareNode.builder().nodeId("plant-1").build()) {
            node.add(Profile.parse("controller[pendulum=1]"), () -> (message, context) -> { });
            node.start();
            // README example begins
            ManagementConfig config = ManagementConfig.builder()
                    .allowDirectory(plugins)                  // plugin jars only from here,
                    .trustStore(trustStore, password)         // and only if a key trusted here signed them
                    .allowRemote("control-1", Set.of(Operation.UPGRADE, Operation.MIGRATE), "controller")
                    .build();                                 // no other node may manage this one
            ManagementService.install(node, config);
            UpgradeResult result = Management.upgrade(node, node.nodeId(), Profile.parse("controller[pendulum=1]"),
                    Implementation.fromJar(plugins.resolve("controller-v2.jar"), "com.example.ControllerV2")).join();
            // README example ends
            assertEquals("com.example.ControllerV2", result.newImplementation());
            assertEquals("com.example.ControllerV2", node.shell(Profile.parse("controller[pendulum=1]")).logicType()
                    .getName());
        }
    }
}
