/**
 * A node from a description: {@link io.etherware.deploy.DeploymentReader} reads and checks an XML
 * deployment file ({@code etherware-deployment.xsd}, explained in the module's DEPLOYMENT.md) into
 * a {@link io.etherware.deploy.Deployment}; {@link io.etherware.deploy.DeployedNode} starts it and
 * closes it in order; {@link io.etherware.deploy.Launcher} is the command ({@code node FILE}) that
 * runs one until SIGTERM. Components that need configuration or resources are made by a
 * {@link io.etherware.deploy.ComponentFactory} named in the file, which reads its
 * {@link io.etherware.deploy.Settings}.
 */
package io.etherware.deploy;
