// gpu/context.cpp: instance and device creation, the up-front feature check, device
// choice, the counting validation messenger, resource factories, and queue submission (with the
// tests' fault injections: a lost device, a hidden feature).
#include "gpu/context.h"

#include "core/error.h"
#include "gpu/check.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace wisp::vk {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool hasExtension(const std::vector<VkExtensionProperties>& list, const char* name)
{
    return std::any_of(list.begin(), list.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::vector<VkExtensionProperties> deviceExtensions(VkPhysicalDevice device)
{
    uint32_t count = 0;
    VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr));
    std::vector<VkExtensionProperties> list(count);
    VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, list.data()));
    return list;
}

std::string lowercase(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

// What WISP_HIDE_FEATURE can hide (test-only), by the names DeviceReport::missing() uses.
struct HideableFeature {
    const char* name;
    bool DeviceReport::*have;
};
constexpr HideableFeature kHideable[] = {
    {"dynamicRendering", &DeviceReport::dynamicRendering},
    {"synchronization2", &DeviceReport::synchronization2},
    {"maintenance4", &DeviceReport::maintenance4},
    {"tessellationShader", &DeviceReport::tessellationShader},
    {"geometryShader", &DeviceReport::geometryShader},
    {"fragmentStoresAndAtomics", &DeviceReport::fragmentStoresAndAtomics},
    {"timestamps", &DeviceReport::timestamps},
    {"shaderBufferFloat32AtomicAdd", &DeviceReport::floatAtomicAdd},
    {"shaderBufferInt64Atomics", &DeviceReport::int64Atomics},
    {"VK_KHR_push_descriptor", &DeviceReport::pushDescriptor},
    {"VK_KHR_swapchain", &DeviceReport::swapchain},
};

// The report members WISP_HIDE_FEATURE=NAME[,NAME...] names (none when it is unset).
std::vector<bool DeviceReport::*> hiddenFeatures()
{
    std::vector<bool DeviceReport::*> hidden;
    const char* env = std::getenv("WISP_HIDE_FEATURE");
    std::stringstream list(env ? env : "");
    for (std::string name; std::getline(list, name, ',');) {
        auto found = std::find_if(std::begin(kHideable), std::end(kHideable),
                                  [&](const HideableFeature& f) { return name == f.name; });
        if (found == std::end(kHideable)) {
            std::string known;
            for (const HideableFeature& f : kHideable)
                known += (known.empty() ? "" : ", ") + std::string(f.name);
            throw UserError("WISP_HIDE_FEATURE: '" + name + "' is not a feature it can hide (known: " + known + ")");
        }
        hidden.push_back(found->have);
    }
    return hidden;
}

// WISP_INJECT_DEVICE_LOST: the queue submission that reports the device lost (0: none).
uint64_t injectedDeviceLoss()
{
    const char* env = std::getenv("WISP_INJECT_DEVICE_LOST");
    if (!env || !*env)
        return 0;
    uint64_t n = 0;
    auto [end, ec] = std::from_chars(env, env + std::strlen(env), n);
    if (ec != std::errc() || *end != '\0' || n == 0)
        throw UserError(std::string("WISP_INJECT_DEVICE_LOST=") + env +
                        ": must be a queue submission number, 1 or more (a test-only fault injection)");
    return n;
}

} // namespace

const char* DeviceReport::typeName() const
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return "CPU";
    default:
        return "other";
    }
}

std::vector<std::string> DeviceReport::missing(bool needSwapchain) const
{
    std::vector<std::string> out;
    auto need = [&](bool have, const char* what) {
        if (!have)
            out.emplace_back(what);
    };
    need(queueFamily != UINT32_MAX, "a graphics+compute queue");
    need(vulkan13, "Vulkan 1.3");
    need(dynamicRendering, "dynamicRendering");
    need(synchronization2, "synchronization2");
    need(maintenance4, "maintenance4");
    need(tessellationShader, "tessellationShader");
    need(geometryShader, "geometryShader");
    need(fragmentStoresAndAtomics, "fragmentStoresAndAtomics");
    need(timestamps, "timestamps (timestampComputeAndGraphics)");
    need(floatAtomicAdd || int64Atomics, "buffer atomics for the hair grid (float add or 64-bit integer)");
    need(pushDescriptor, "VK_KHR_push_descriptor");
    if (needSwapchain)
        need(swapchain, "VK_KHR_swapchain");
    return out;
}

int deviceTypeRank(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return 3;
    default:
        return 4;
    }
}

std::vector<DeviceReport> queryDevices(VkInstance instance)
{
    std::vector<bool DeviceReport::*> hidden = hiddenFeatures();
    uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));

    std::vector<DeviceReport> reports;
    for (uint32_t i = 0; i < count; ++i) {
        VkPhysicalDevice pd = devices[i];
        DeviceReport r;
        r.index = i;

        VkPhysicalDeviceDriverProperties driver{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
        VkPhysicalDeviceProperties2 props{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &driver};
        vkGetPhysicalDeviceProperties2(pd, &props);
        const VkPhysicalDeviceLimits& limits = props.properties.limits;
        r.name = props.properties.deviceName;
        r.type = props.properties.deviceType;
        r.apiVersion = props.properties.apiVersion;
        r.driverName = driver.driverName;
        r.driverInfo = driver.driverInfo;
        r.vulkan13 = props.properties.apiVersion >= VK_API_VERSION_1_3;
        r.timestampPeriodNs = limits.timestampPeriod;
        r.maxTessellationGenerationLevel = limits.maxTessellationGenerationLevel;
        r.maxTessellationPatchSize = limits.maxTessellationPatchSize;
        r.maxGeometryOutputVertices = limits.maxGeometryOutputVertices;
        r.maxStorageBufferRange = limits.maxStorageBufferRange;
        r.colorDepthSampleCounts = limits.framebufferColorSampleCounts & limits.framebufferDepthSampleCounts;

        std::vector<VkExtensionProperties> extensions = deviceExtensions(pd);
        r.pushDescriptor = hasExtension(extensions, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
        r.swapchain = hasExtension(extensions, VK_KHR_SWAPCHAIN_EXTENSION_NAME);
        bool atomicFloatExt = hasExtension(extensions, VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);

        VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomicFloat{
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
        VkPhysicalDeviceVulkan12Features f12{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                             .pNext = atomicFloatExt ? &atomicFloat : nullptr};
        VkPhysicalDeviceVulkan13Features f13{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                             .pNext = &f12};
        VkPhysicalDeviceFeatures2 features{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
                                           .pNext = r.vulkan13 ? &f13 : nullptr};
        vkGetPhysicalDeviceFeatures2(pd, &features);
        r.dynamicRendering = r.vulkan13 && f13.dynamicRendering;
        r.synchronization2 = r.vulkan13 && f13.synchronization2;
        r.maintenance4 = r.vulkan13 && f13.maintenance4;
        r.tessellationShader = features.features.tessellationShader;
        r.geometryShader = features.features.geometryShader;
        r.fragmentStoresAndAtomics = features.features.fragmentStoresAndAtomics;
        r.vertexPipelineStoresAndAtomics = features.features.vertexPipelineStoresAndAtomics;
        r.pipelineStatisticsQuery = features.features.pipelineStatisticsQuery;
        r.floatAtomicAdd = r.vulkan13 && atomicFloatExt && atomicFloat.shaderBufferFloat32AtomicAdd;
        r.int64Atomics = r.vulkan13 && features.features.shaderInt64 && f12.shaderBufferInt64Atomics;

        uint32_t familyCount = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &familyCount, nullptr);
        std::vector<VkQueueFamilyProperties> families(familyCount);
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &familyCount, families.data());
        for (uint32_t f = 0; f < familyCount; ++f) {
            VkQueueFlags want = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
            if ((families[f].queueFlags & want) == want) {
                r.queueFamily = f;
                r.timestampValidBits = families[f].timestampValidBits;
                break;
            }
        }
        r.timestamps = limits.timestampComputeAndGraphics && r.timestampValidBits > 0;
        for (bool DeviceReport::*have : hidden)
            r.*have = false;

        VkPhysicalDeviceMemoryProperties memory;
        vkGetPhysicalDeviceMemoryProperties(pd, &memory);
        for (uint32_t h = 0; h < memory.memoryHeapCount; ++h)
            if (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
                r.deviceLocalBytes = std::max<uint64_t>(r.deviceLocalBytes, memory.memoryHeaps[h].size);
        reports.push_back(std::move(r));
    }
    return reports;
}

const DeviceReport& selectDevice(const std::vector<DeviceReport>& devices, const std::string& selector,
                                 bool needSwapchain)
{
    if (devices.empty())
        throw UserError("no Vulkan device found: install a GPU driver, or Mesa's CPU driver "
                        "(Debian package mesa-vulkan-drivers), and check VK_ICD_FILENAMES");
    auto listing = [&] {
        std::ostringstream s;
        for (const DeviceReport& d : devices)
            s << (d.index ? ", " : "") << d.index << " '" << d.name << "'";
        return s.str();
    };
    auto requireUsable = [&](const DeviceReport& d) -> const DeviceReport& {
        std::vector<std::string> missing = d.missing(needSwapchain);
        if (!missing.empty()) {
            std::ostringstream s;
            s << "Vulkan device " << d.index << " '" << d.name << "' lacks what Wisp needs: ";
            for (size_t i = 0; i < missing.size(); ++i)
                s << (i ? ", " : "") << missing[i];
            throw UserError(s.str());
        }
        return d;
    };

    if (!selector.empty()) {
        bool numeric = std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); });
        if (numeric) {
            unsigned long index = std::stoul(selector);
            if (index >= devices.size())
                throw UserError("--gpu " + selector + ": no such device index (devices: " + listing() + ")");
            return requireUsable(devices[index]);
        }
        for (const DeviceReport& d : devices)
            if (lowercase(d.name).find(lowercase(selector)) != std::string::npos)
                return requireUsable(d);
        throw UserError("--gpu " + selector + ": no device name contains it (devices: " + listing() + ")");
    }

    std::vector<const DeviceReport*> order;
    for (const DeviceReport& d : devices)
        order.push_back(&d);
    std::stable_sort(order.begin(), order.end(), [](const DeviceReport* a, const DeviceReport* b) {
        return deviceTypeRank(a->type) < deviceTypeRank(b->type);
    });
    for (const DeviceReport* d : order)
        if (d->missing(needSwapchain).empty())
            return *d;
    return requireUsable(*order.front()); // throws, naming what the best device lacks
}

Context::Context(const ContextOptions& options) : deviceLostAtSubmission_(injectedDeviceLoss())
{
    VkApplicationInfo app{.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                          .pApplicationName = "wisp",
                          .applicationVersion = VK_MAKE_VERSION(0, 1, 0),
                          .pEngineName = "wisp",
                          .apiVersion = VK_API_VERSION_1_3};

    uint32_t extensionCount = 0;
    VkResult enumerated = vkEnumerateInstanceExtensionProperties(nullptr, &extensionCount, nullptr);
    if (enumerated != VK_SUCCESS)
        throw UserError("cannot load Vulkan (" + std::string(resultName(enumerated)) +
                        "): install libvulkan1 and a driver (mesa-vulkan-drivers for the CPU driver)");
    std::vector<VkExtensionProperties> available(extensionCount);
    VK_CHECK(vkEnumerateInstanceExtensionProperties(nullptr, &extensionCount, available.data()));

    std::vector<const char*> extensions;
    for (const std::string& e : options.instanceExtensions)
        extensions.push_back(e.c_str());
    bool debugUtils = hasExtension(available, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (debugUtils)
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (options.validation && !debugUtils)
        throw UserError("--validation: the Vulkan loader offers no VK_EXT_debug_utils");

    std::vector<const char*> layers;
    if (options.validation) {
        uint32_t layerCount = 0;
        VK_CHECK(vkEnumerateInstanceLayerProperties(&layerCount, nullptr));
        std::vector<VkLayerProperties> layerList(layerCount);
        VK_CHECK(vkEnumerateInstanceLayerProperties(&layerCount, layerList.data()));
        bool found = std::any_of(layerList.begin(), layerList.end(), [](const VkLayerProperties& l) {
            return std::strcmp(l.layerName, kValidationLayer) == 0;
        });
        if (!found)
            throw UserError("--validation: the Khronos validation layer is not installed "
                            "(Debian package vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
    }

    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity =
            VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = &Context::onMessage,
        .pUserData = this};
    VkValidationFeatureEnableEXT syncValidation = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT validationFeatures{.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
                                               .pNext = &messengerInfo,
                                               .enabledValidationFeatureCount = 1,
                                               .pEnabledValidationFeatures = &syncValidation};
    const void* instanceNext = nullptr;
    if (options.validation)
        instanceNext = options.synchronizationValidation ? static_cast<const void*>(&validationFeatures)
                                                         : static_cast<const void*>(&messengerInfo);
    VkInstanceCreateInfo instanceInfo{.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                                      .pNext = instanceNext,
                                      .pApplicationInfo = &app,
                                      .enabledLayerCount = static_cast<uint32_t>(layers.size()),
                                      .ppEnabledLayerNames = layers.data(),
                                      .enabledExtensionCount = static_cast<uint32_t>(extensions.size()),
                                      .ppEnabledExtensionNames = extensions.data()};
    VkResult created = vkCreateInstance(&instanceInfo, nullptr, &instance_);
    if (created == VK_ERROR_INCOMPATIBLE_DRIVER)
        throw UserError("no Vulkan 1.3 driver found: install a GPU driver, or Mesa's CPU driver "
                        "(Debian package mesa-vulkan-drivers), and check VK_ICD_FILENAMES");
    VK_CHECK(created);

    try {
        if (options.validation) {
            auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
            VK_CHECK(create(instance_, &messengerInfo, nullptr, &messenger_));
        }
        if (debugUtils)
            setObjectName_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
                vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));

        std::vector<DeviceReport> devices = queryDevices(instance_);
        report_ = selectDevice(devices, options.gpu, options.presentation);
        uint32_t count = 0;
        VK_CHECK(vkEnumeratePhysicalDevices(instance_, &count, nullptr));
        std::vector<VkPhysicalDevice> physical(count);
        VK_CHECK(vkEnumeratePhysicalDevices(instance_, &count, physical.data()));
        physical_ = physical[report_.index];
        vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);

        float priority = 1.0f;
        VkDeviceQueueCreateInfo queueInfo{.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                          .queueFamilyIndex = report_.queueFamily,
                                          .queueCount = 1,
                                          .pQueuePriorities = &priority};
        std::vector<const char*> deviceExtensionNames = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
        if (options.presentation)
            deviceExtensionNames.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
        VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomicFloat{
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT,
            .shaderBufferFloat32Atomics = VK_TRUE,
            .shaderBufferFloat32AtomicAdd = VK_TRUE};
        if (report_.floatAtomicAdd)
            deviceExtensionNames.push_back(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
        VkPhysicalDeviceVulkan12Features f12{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                             .pNext = report_.floatAtomicAdd ? &atomicFloat : nullptr,
                                             .shaderBufferInt64Atomics = report_.int64Atomics};
        VkPhysicalDeviceVulkan13Features f13{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                             .pNext = &f12,
                                             .synchronization2 = VK_TRUE,
                                             .dynamicRendering = VK_TRUE,
                                             .maintenance4 = VK_TRUE};
        // WISP_SHADER_STATS=1 (profiling aid): the driver's statistics of every compute pipeline
        // (registers, shared memory, spills) printed as it is made, where the device reports them.
        VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executableInfo{
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR,
            .pipelineExecutableInfo = VK_TRUE};
        if (std::getenv("WISP_SHADER_STATS")) {
            for (const VkExtensionProperties& e : deviceExtensions(physical_))
                if (std::string(e.extensionName) == VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME)
                    shaderStats_ = true;
            if (shaderStats_) {
                deviceExtensionNames.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
                executableInfo.pNext = f12.pNext;
                f12.pNext = &executableInfo;
            }
        }
        VkPhysicalDeviceFeatures2 features{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &f13};
        features.features.tessellationShader = VK_TRUE;
        features.features.geometryShader = VK_TRUE;
        features.features.fragmentStoresAndAtomics = VK_TRUE;
        features.features.vertexPipelineStoresAndAtomics = report_.vertexPipelineStoresAndAtomics;
        features.features.pipelineStatisticsQuery = report_.pipelineStatisticsQuery;
        features.features.shaderInt64 = report_.int64Atomics;
        VkDeviceCreateInfo deviceInfo{.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                                      .pNext = &features,
                                      .queueCreateInfoCount = 1,
                                      .pQueueCreateInfos = &queueInfo,
                                      .enabledExtensionCount = static_cast<uint32_t>(deviceExtensionNames.size()),
                                      .ppEnabledExtensionNames = deviceExtensionNames.data()};
        VK_CHECK(vkCreateDevice(physical_, &deviceInfo, nullptr, &device_));
        vkGetDeviceQueue(device_, report_.queueFamily, 0, &queue_);
        cmdPushDescriptorSet_ =
            reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
        uploadPool_ = createCommandPool("context.upload");
    } catch (...) {
        destroy();
        throw;
    }
}

Context::~Context()
{
    destroy();
}

void Context::destroy()
{
    uploadPool_.reset();
    if (device_) {
        vkDeviceWaitIdle(device_); // a lost device returns VK_ERROR_DEVICE_LOST at once: nothing left to wait for
        vkDestroyDevice(device_, nullptr);
        device_ = VK_NULL_HANDLE;
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        destroy(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance_) {
        vkDestroyInstance(instance_, nullptr);
        instance_ = VK_NULL_HANDLE;
    }
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* user)
{
    auto* self = static_cast<Context*>(user);
    self->validationMessages_.fetch_add(1);
    const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
    std::fprintf(stderr, "wisp: validation %s: %s\n", level, data->pMessage);
    return VK_FALSE;
}

void Context::setName(uint64_t handle, VkObjectType type, const char* name) const
{
    if (!setObjectName_ || !handle)
        return;
    VkDebugUtilsObjectNameInfoEXT info{.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT,
                                       .objectType = type,
                                       .objectHandle = handle,
                                       .pObjectName = name};
    VK_CHECK(setObjectName_(device_, &info));
}

void Context::pushDescriptorSet(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint, VkPipelineLayout layout,
                                uint32_t set, uint32_t count, const VkWriteDescriptorSet* writes) const
{
    cmdPushDescriptorSet_(cmd, bindPoint, layout, set, count, writes);
}

uint32_t Context::memoryTypeIndex(uint32_t typeBits, VkMemoryPropertyFlags required,
                                  VkMemoryPropertyFlags preferred) const
{
    for (VkMemoryPropertyFlags want : {required | preferred, required})
        for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
            if ((typeBits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & want) == want)
                return i;
    throw std::runtime_error("no Vulkan memory type matches the resource's requirements");
}

namespace {

VkDeviceMemory allocate(const Context& ctx, VkMemoryRequirements req, Memory use, const char* name)
{
    VkMemoryPropertyFlags required = 0;
    VkMemoryPropertyFlags preferred = 0;
    switch (use) {
    case Memory::DeviceLocal:
        preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
        break;
    case Memory::Upload:
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        break;
    case Memory::Readback:
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
        break;
    }
    VkMemoryAllocateInfo info{.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                              .allocationSize = req.size,
                              .memoryTypeIndex = ctx.memoryTypeIndex(req.memoryTypeBits, required, preferred)};
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkResult result = vkAllocateMemory(ctx.device(), &info, nullptr, &memory);
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
        throw UserError(std::string("out of ") + (result == VK_ERROR_OUT_OF_DEVICE_MEMORY ? "GPU" : "host") +
                        " memory allocating '" + name + "': " + std::to_string(req.size) + " bytes needed, device '" +
                        ctx.report().name + "' has " + std::to_string(ctx.report().deviceLocalBytes) +
                        " bytes of device-local memory in all");
    VK_CHECK(result);
    trackDeviceMemory(memory, req.size);
    ctx.setName(memory, VK_OBJECT_TYPE_DEVICE_MEMORY, name);
    return memory;
}

} // namespace

Buffer Context::createBuffer(const BufferDesc& desc) const
{
    VkBufferCreateInfo info{.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                            .size = desc.size,
                            .usage = desc.usage,
                            .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
    VkBuffer buffer = VK_NULL_HANDLE;
    VK_CHECK(vkCreateBuffer(device_, &info, nullptr, &buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, buffer, &req);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    try {
        memory = allocate(*this, req, desc.memory, desc.name);
    } catch (...) {
        vkDestroyBuffer(device_, buffer, nullptr);
        throw;
    }
    VK_CHECK(vkBindBufferMemory(device_, buffer, memory, 0));
    void* mapped = nullptr;
    if (desc.memory != Memory::DeviceLocal)
        VK_CHECK(vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, &mapped));
    setName(buffer, VK_OBJECT_TYPE_BUFFER, desc.name);
    return Buffer(device_, buffer, memory, desc.size, mapped);
}

Buffer Context::createBufferWithData(const BufferDesc& desc, const void* data, size_t bytes) const
{
    BufferDesc target = desc;
    target.usage |= kTransferDst;
    Buffer buffer = createBuffer(target);
    std::string stagingName = std::string(desc.name) + ".staging";
    Buffer staging =
        createBuffer({.size = bytes, .usage = kTransferSrc, .memory = Memory::Upload, .name = stagingName.c_str()});
    std::memcpy(staging.mapped(), data, bytes);
    submitAndWait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{.size = bytes};
        vkCmdCopyBuffer(cmd, staging, buffer, 1, &region);
    });
    return buffer;
}

Image Context::createImage(const ImageDesc& desc) const
{
    VkImageCreateInfo info{.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
                           .imageType = VK_IMAGE_TYPE_2D,
                           .format = desc.format,
                           .extent = {desc.extent.width, desc.extent.height, 1},
                           .mipLevels = 1,
                           .arrayLayers = desc.layers,
                           .samples = desc.samples,
                           .tiling = VK_IMAGE_TILING_OPTIMAL,
                           .usage = desc.usage,
                           .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
                           .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
    VkImage image = VK_NULL_HANDLE;
    VK_CHECK(vkCreateImage(device_, &info, nullptr, &image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device_, image, &req);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    try {
        memory = allocate(*this, req, Memory::DeviceLocal, desc.name);
    } catch (...) {
        vkDestroyImage(device_, image, nullptr);
        throw;
    }
    VK_CHECK(vkBindImageMemory(device_, image, memory, 0));
    VkImageViewCreateInfo viewInfo{.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                                   .image = image,
                                   .viewType = desc.layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D,
                                   .format = desc.format,
                                   .subresourceRange = {isDepthFormat(desc.format)
                                                            ? VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT)
                                                            : VkImageAspectFlags(VK_IMAGE_ASPECT_COLOR_BIT),
                                                        0, 1, 0, desc.layers}};
    VkImageView view = VK_NULL_HANDLE;
    VK_CHECK(vkCreateImageView(device_, &viewInfo, nullptr, &view));
    setName(image, VK_OBJECT_TYPE_IMAGE, desc.name);
    setName(view, VK_OBJECT_TYPE_IMAGE_VIEW, desc.name);
    return Image(device_, image, memory, view, desc);
}

Fence Context::createFence(bool signaled, const char* name) const
{
    VkFenceCreateInfo info{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO,
                           .flags = signaled ? VkFenceCreateFlags(VK_FENCE_CREATE_SIGNALED_BIT) : 0u};
    VkFence fence = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFence(device_, &info, nullptr, &fence));
    setName(fence, VK_OBJECT_TYPE_FENCE, name);
    return Fence(device_, fence);
}

Semaphore Context::createSemaphore(const char* name) const
{
    VkSemaphoreCreateInfo info{.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSemaphore(device_, &info, nullptr, &semaphore));
    setName(semaphore, VK_OBJECT_TYPE_SEMAPHORE, name);
    return Semaphore(device_, semaphore);
}

CommandPool Context::createCommandPool(const char* name) const
{
    VkCommandPoolCreateInfo info{.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                 .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                 .queueFamilyIndex = report_.queueFamily};
    VkCommandPool pool = VK_NULL_HANDLE;
    VK_CHECK(vkCreateCommandPool(device_, &info, nullptr, &pool));
    setName(pool, VK_OBJECT_TYPE_COMMAND_POOL, name);
    return CommandPool(device_, pool);
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const
{
    VkCommandBufferAllocateInfo allocInfo{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                          .commandPool = uploadPool_,
                                          .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                          .commandBufferCount = 1};
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VK_CHECK(vkAllocateCommandBuffers(device_, &allocInfo, &cmd));
    VkCommandBufferBeginInfo begin{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                   .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));
    Fence fence = createFence(false, "context.submitAndWait");
    VkCommandBufferSubmitInfo cmdInfo{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 info{
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1, .pCommandBufferInfos = &cmdInfo};
    VK_CHECK(queueSubmit(info, fence));
    VkFence waitFence = fence;
    VK_CHECK(vkWaitForFences(device_, 1, &waitFence, VK_TRUE, UINT64_MAX));
    vkFreeCommandBuffers(device_, uploadPool_, 1, &cmd);
}

VkResult Context::queueSubmit(const VkSubmitInfo2& info, VkFence fence) const
{
    ++submissions_;
    if (deviceLostAtSubmission_ > 0 && submissions_ >= deviceLostAtSubmission_)
        return VK_ERROR_DEVICE_LOST; // injected: see context.h
    return vkQueueSubmit2(queue_, 1, &info, fence);
}

} // namespace wisp::vk

namespace wisp::vk {

std::vector<DeviceReport> enumerateDevices()
{
    VkApplicationInfo app{
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .pApplicationName = "wisp", .apiVersion = VK_API_VERSION_1_3};
    VkInstanceCreateInfo info{.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &app};
    VkInstance instance = VK_NULL_HANDLE;
    VkResult created = vkCreateInstance(&info, nullptr, &instance);
    if (created == VK_ERROR_INCOMPATIBLE_DRIVER)
        return {};
    if (created != VK_SUCCESS)
        throw UserError(std::string("cannot create a Vulkan instance (") + resultName(created) +
                        "): install libvulkan1 and a driver (mesa-vulkan-drivers for the CPU driver)");
    try {
        std::vector<DeviceReport> reports = queryDevices(instance);
        vkDestroyInstance(instance, nullptr);
        return reports;
    } catch (...) {
        vkDestroyInstance(instance, nullptr);
        throw;
    }
}

} // namespace wisp::vk
